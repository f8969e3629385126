//! The machine setup: offset registers, work offsets and machine parameters (`SETUP.toml`).

use std::collections::BTreeMap;

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Length units of the values in a setup file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Millimetres (the default).
    #[default]
    Mm,
    /// Inches.
    Inch,
}

impl Units {
    /// Millimetres per unit.
    pub fn mm(self) -> f64 {
        [1.0, 25.4][self as usize]
    }
}

/// One offset register (addressed by H for length and D for radius), in millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Register {
    /// Tool length geometry.
    pub length: f64,
    /// Tool radius geometry.
    pub radius: f64,
    /// Tool length wear (added to the geometry).
    pub length_wear: f64,
    /// Tool radius wear (added to the geometry).
    pub radius_wear: f64,
    /// The tip direction of a lathe tool (LinuxCNC's `Q`, Fanuc's imaginary tool nose): 1–8 report
    /// compensation in G18 at the imaginary tip; 0 (a mill) and 9 at the nose centre.
    #[serde(skip_serializing_if = "is_zero")]
    pub orientation: u8,
}

// serde's `skip_serializing_if` hands the field by reference.
#[allow(clippy::trivially_copy_pass_by_ref)]
fn is_zero(v: &u8) -> bool {
    *v == 0
}

/// How cutter radius compensation goes round an outside corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CornerMode {
    /// An arc of the tool radius about the programmed corner (LinuxCNC).
    Arc,
    /// The offset paths' intersection, with two extra vectors past 90° (the Fanuc family).
    Intersection,
}

/// Machine parameters that change how programs run.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Machine {
    /// Rapid traverse rate in mm/min, for the time estimate: the speed along the path of a
    /// G00 move (linear interpolated) unless `rapid_xyz_mm_per_min` limits an axis further.
    pub rapid_mm_per_min: f64,
    /// Rapid rate of each axis X, Y, Z in mm/min where they differ (often a slower Z): a rapid runs
    /// as fast as its slowest axis allows. Unset: every axis at `rapid_mm_per_min`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rapid_xyz_mm_per_min: Option<[f64; 3]>,
    /// Acceleration along the path in mm/s², for the time estimate (trapezoidal velocity profiles).
    /// Zero: none is modelled (every move runs at its feed from end to end).
    pub acceleration_mm_per_s2: f64,
    /// Most blocks executed before a run is stopped as runaway.
    pub max_blocks: u64,
    /// Most work a run does inside its blocks before it stops as runaway: each expression term and
    /// O-word line searched counts one, a diagnostic met again 8, an arc's extra turn 64.
    pub max_work: u64,
    /// The machine's travel (gauge line) in machine coordinates, mm, lowest and highest X, Y, Z: a
    /// move past it is an overtravel alarm (`E-OVERTRAVEL`). Unset: not checked.
    pub travel_mm: Option<[[f64; 3]; 2]>,
    /// Most motion events a run may produce before it stops: a bound on the toolpath's memory
    /// (about 50 bytes a segment), so a runaway program cannot exhaust a browser tab.
    pub max_motions: u64,
    /// Largest difference between an arc's start and end radius before it is an alarm (mm).
    pub arc_tolerance_mm: f64,
    /// Numbers without a decimal point are mm (not least increments). Unset: the dialect's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calculator_input: Option<bool>,
    /// Reference points P1 (G28) to P4 (G30) in machine coordinates, mm; missing: the origin.
    pub reference_points: Vec<[f64; 3]>,
    /// Measured angles in degrees (LNC G168 Q1–Q4 rotates by them), from the machine's probing.
    pub measured_angles: Vec<f64>,
    /// The retract d between pecks of G73 and G83 in mm (KT data parameter P230, Syntec Pr4002;
    /// the manuals' default 1.000 mm). LinuxCNC's rs274ngc retracts a fixed 0.010 inch instead.
    pub peck_retract_mm: f64,
    /// The way the boring bar shifts from the wall at G76/G87's oriented stop (Syntec Pr4020, KT
    /// P018 bits 4–5: ±X or ±Y only), written `"+X"`, `"-Y"` …
    pub shift_direction: ShiftDirection,
    /// Syntec Pr4001 = 1: peck tapping (G74/G84 with Q) backs out by `peck_retract_mm` between
    /// pecks (high-speed, TYPE II); Pr4001 = 0 (the default here) backs out to R (TYPE III).
    pub high_speed_peck_tapping: bool,
    /// Syntec Pr4008 = 1 (fast drilling, TYPE II): G81 retracts at the `F2=` feed when one is
    /// given. Pr4008 = 0 (normal drilling) ignores `F2=` and retracts at rapid.
    pub fast_drilling: bool,
    /// How compensation cuts outside corners. Unset: `arc` for LinuxCNC, else `intersection`.
    pub corner_mode: Option<CornerMode>,
    /// Gouges under compensation alarm (Syntec 3819, the overcut check) rather than warn.
    pub overcut_alarm: bool,
    /// Whether the control swaps G41 and G42 under a mirror of one plane axis (Fanuc's mirror
    /// image); `false` takes the side as written (Syntec). Unset: `false` for Syntec and LinuxCNC.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mirror_swaps_comp_side: Option<bool>,
}

/// An axis direction for the G76/G87 shift.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
pub enum ShiftDirection {
    /// +X (Syntec Pr4020 = 0, the default).
    #[default]
    #[serde(rename = "+X")]
    PlusX,
    /// −X.
    #[serde(rename = "-X")]
    MinusX,
    /// +Y.
    #[serde(rename = "+Y")]
    PlusY,
    /// −Y.
    #[serde(rename = "-Y")]
    MinusY,
    /// +Z.
    #[serde(rename = "+Z")]
    PlusZ,
    /// −Z.
    #[serde(rename = "-Z")]
    MinusZ,
}

impl ShiftDirection {
    /// The unit vector of the direction (machine axes).
    pub fn vector(self) -> DVec3 {
        let mut v = DVec3::ZERO;
        v[self as usize / 2] = [1.0, -1.0][self as usize % 2];
        v
    }
}

impl Default for Machine {
    fn default() -> Self {
        Machine {
            rapid_mm_per_min: 10_000.0,
            rapid_xyz_mm_per_min: None,
            acceleration_mm_per_s2: 1000.0,
            max_blocks: 20_000_000,
            max_work: 200_000_000,
            max_motions: 10_000_000,
            travel_mm: None,
            arc_tolerance_mm: 0.01,
            calculator_input: None,
            reference_points: Vec::new(),
            measured_angles: Vec::new(),
            peck_retract_mm: 1.0,
            shift_direction: ShiftDirection::PlusX,
            fast_drilling: true,
            high_speed_peck_tapping: false,
            corner_mode: None,
            overcut_alarm: false,
            mirror_swaps_comp_side: None,
        }
    }
}

/// Everything about the machine a program runs on that the program itself does not say.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Setup {
    /// Offset registers by number.
    pub registers: BTreeMap<u32, Register>,
    /// Work offsets by canonical name (`G54`, `G54.1P7`, `G59.3`), in millimetres.
    pub work_offsets: BTreeMap<String, DVec3>,
    /// Machine parameters.
    pub machine: Machine,
    /// The `[stock]` table as written, for the stock crate to read and check.
    pub stock: Option<toml::Table>,
    /// The `[tools.N]` tables as written (mm), by tool number, read and checked like `stock`.
    pub tools: BTreeMap<u32, toml::Table>,
}

/// Why a setup file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The TOML is malformed or has unknown keys.
    #[error("{0}")]
    Toml(#[from] toml::de::Error),
    /// A work offset name that no control has.
    #[error("unknown work offset `{0}` (expected G54…G59, G54.1P1…G54.1P48 or G59.1…G59.9)")]
    WorkOffset(String),
    /// The setup could not be written as TOML (a number TOML cannot hold).
    #[error("{0}")]
    Write(#[from] toml::ser::Error),
    /// A value outside the range the key allows (or not a number at all).
    #[error("`{key}` must be from {min} to {max} (it is {value})")]
    Range {
        /// The key, `machine.rapid_mm_per_min` or `registers.3.radius`.
        key: String,
        /// The lowest value allowed.
        min: f64,
        /// The highest value allowed.
        max: f64,
        /// The value given.
        value: f64,
    },
    /// A tool orientation outside 0–9.
    #[error("`registers.{0}.orientation` must be 0 to 9")]
    Orientation(u32),
}

/// The largest length a setup may give (an offset, a travel limit, a reference point), in its
/// units: a kilometre, past any machine, so an absurd value is refused rather than computed.
pub const MAX_LENGTH: f64 = 1.0e6;

/// The largest rate a setup may give (mm/min, mm/s²).
pub const MAX_RATE: f64 = 1.0e7;

/// The highest `[machine] max_work` (at ten million terms a second, days of running).
const MAX_WORK: f64 = 1.0e13;

/// `value` for `key` when it lies in `min..=max`; a range error naming the key otherwise.
fn in_range(key: impl Into<String>, value: f64, min: f64, max: f64) -> Result<f64, SetupError> {
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(SetupError::Range {
            key: key.into(),
            min,
            max,
            value,
        })
    }
}

/// Checks every length of `values` is within ±[`MAX_LENGTH`], and scales it by `k` (to mm).
fn lengths_in_range(key: &str, values: &mut [f64], k: f64) -> Result<(), SetupError> {
    for v in values {
        *v = in_range(key, *v, -MAX_LENGTH, MAX_LENGTH)? * k;
    }
    Ok(())
}

#[derive(Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
struct SetupFile {
    units: Units,
    registers: BTreeMap<u32, Register>,
    work_offsets: BTreeMap<String, [f64; 3]>,
    machine: Machine,
    #[serde(skip_serializing_if = "Option::is_none")]
    stock: Option<toml::Table>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    tools: BTreeMap<u32, toml::Table>,
}

impl Setup {
    /// Reads a `SETUP.toml` text; lengths are converted to millimetres.
    pub fn from_toml(text: &str) -> Result<Self, SetupError> {
        let file: SetupFile = toml::from_str(text)?;
        let k = file.units.mm();
        let mut setup = Setup {
            machine: file.machine,
            stock: file.stock,
            tools: file.tools,
            ..Setup::default()
        };
        for (n, mut r) in file.registers {
            for (name, v) in [
                ("length", &mut r.length),
                ("radius", &mut r.radius),
                ("length_wear", &mut r.length_wear),
                ("radius_wear", &mut r.radius_wear),
            ] {
                lengths_in_range(&format!("registers.{n}.{name}"), std::slice::from_mut(v), k)?;
            }
            if r.orientation > 9 {
                return Err(SetupError::Orientation(n));
            }
            setup.registers.insert(n, r);
        }
        for (name, mut v) in file.work_offsets {
            let canonical =
                canonical_work_offset(&name).ok_or_else(|| SetupError::WorkOffset(name.clone()))?;
            lengths_in_range(&format!("work_offsets.{name}"), &mut v, k)?;
            setup.work_offsets.insert(canonical, DVec3::from_array(v));
        }
        if let Some(travel) = &mut setup.machine.travel_mm {
            lengths_in_range("machine.travel_mm", travel.as_flattened_mut(), k)?;
            let [lo, hi] = *travel;
            *travel = [
                std::array::from_fn(|i| lo[i].min(hi[i])),
                std::array::from_fn(|i| lo[i].max(hi[i])),
            ];
        }
        for point in &mut setup.machine.reference_points {
            lengths_in_range("machine.reference_points", point, k)?;
        }
        let m = &setup.machine;
        // A rate of zero would make moves take forever, a work limit of zero stop every run.
        let rapids = m.rapid_xyz_mm_per_min.iter().flatten();
        let angles = m.measured_angles.iter();
        let rapid = ("rapid_mm_per_min", m.rapid_mm_per_min, 1.0, MAX_RATE);
        let acc = m.acceleration_mm_per_s2;
        for (key, value, min, max) in std::iter::once(rapid)
            .chain(rapids.map(|&v| ("rapid_xyz_mm_per_min", v, 1.0, MAX_RATE)))
            .chain([
                ("acceleration_mm_per_s2", acc, 0.0, MAX_RATE),
                ("arc_tolerance_mm", m.arc_tolerance_mm, 0.0, 1000.0),
                ("max_work", m.max_work as f64, 1.0, MAX_WORK),
                ("peck_retract_mm", m.peck_retract_mm, 0.0, 1000.0),
            ])
            .chain(angles.map(|&v| ("measured_angles", v, -360.0, 360.0)))
        {
            in_range(format!("machine.{key}"), value, min, max)?;
        }
        Ok(setup)
    }

    /// Writes the setup as a `SETUP.toml` text in millimetres, which [`Setup::from_toml`] reads
    /// back to an equal setup (the settings window's export and the app's saved settings).
    pub fn to_toml(&self) -> Result<String, SetupError> {
        let file = SetupFile {
            units: Units::Mm,
            registers: self.registers.clone(),
            work_offsets: self
                .work_offsets
                .iter()
                .map(|(k, v)| (k.clone(), v.to_array()))
                .collect(),
            machine: self.machine.clone(),
            stock: self.stock.clone(),
            tools: self.tools.clone(),
        };
        Ok(toml::to_string(&file)?)
    }

    /// Reference point `n` (1: G28, 2–4: G30) in machine coordinates, mm (else the origin).
    pub fn reference_point(&self, n: usize) -> DVec3 {
        n.checked_sub(1)
            .and_then(|i| self.machine.reference_points.get(i))
            .map_or(DVec3::ZERO, |p| DVec3::from_array(*p))
    }

    /// Register `n`'s length and radius, geometry plus wear (zeros when the setup lacks it).
    pub(crate) fn offsets(&self, n: u32) -> (f64, f64) {
        let r = self.registers.get(&n).copied().unwrap_or_default();
        (r.length + r.length_wear, r.radius + r.radius_wear)
    }

    /// The offset of a work coordinate system by canonical name (zero when not set).
    pub fn work_offset(&self, name: &str) -> DVec3 {
        self.work_offsets.get(name).copied().unwrap_or(DVec3::ZERO)
    }
}

/// Normalises a work offset name (`g54.1 p7` → `G54.1P7`); `None` for names no control has.
pub(crate) fn canonical_work_offset(name: &str) -> Option<String> {
    let compact = name.replace(char::is_whitespace, "").to_ascii_uppercase();
    let ok = match compact.as_str() {
        "G54" | "G55" | "G56" | "G57" | "G58" | "G59" => true,
        s if s.starts_with("G54.1P") => s[6..].parse::<u32>().is_ok_and(|p| (1..=48).contains(&p)),
        s if s.starts_with("G59.") => s[4..].parse::<u32>().is_ok_and(|p| (1..=9).contains(&p)),
        _ => false,
    };
    ok.then_some(compact)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn reads_registers_offsets_and_units() {
        let s = Setup::from_toml(
            "units = \"inch\"\n[registers.1]\nlength = 1.0\nradius = 0.25\n[work_offsets]\nG54 = [1, 2, 3]\n\"g54.1 p7\" = [0, 0, 1]\n[machine]\nrapid_mm_per_min = 5000\n",
        )
        .unwrap();
        assert_eq!(s.registers[&1].length, 25.4);
        assert_eq!(s.registers[&1].radius, 6.35);
        assert!(
            s.work_offset("G54")
                .abs_diff_eq(DVec3::new(25.4, 50.8, 76.2), 1e-9)
        );
        assert_eq!(s.work_offset("G54.1P7"), DVec3::new(0.0, 0.0, 25.4));
        assert_eq!(s.machine.rapid_mm_per_min, 5000.0);
    }

    #[test]
    fn writes_toml_that_reads_back_equal() {
        let mut s = Setup::from_toml(
            "[registers.3]\nlength = 101.5\nradius_wear = -0.02\n[work_offsets]\n\"G54.1P7\" = [1, 2, 3]\n[machine]\nrapid_xyz_mm_per_min = [1, 2, 3]\nreference_points = [[0, 0, 100]]\n",
        )
        .unwrap();
        s.machine.calculator_input = Some(true);
        let stock = "[stock]\nmin = [0, 0, -20]\nmax = [100, 50, 0]\n[tools.3]\ndiameter = 6.0\n";
        let with_stock = Setup::from_toml(stock).unwrap();
        assert_eq!(
            with_stock.stock.as_ref().unwrap()["max"][0].as_integer(),
            Some(100)
        );
        assert_eq!(with_stock.tools[&3]["diameter"].as_float(), Some(6.0));
        s.stock = with_stock.stock;
        s.tools = with_stock.tools;
        let text = s.to_toml().unwrap();
        assert_eq!(Setup::from_toml(&text).unwrap(), s, "{text}");
        assert_eq!(
            Setup::from_toml(&Setup::default().to_toml().unwrap()).unwrap(),
            Setup::default()
        );
    }

    #[test]
    fn reads_lathe_orientations_and_the_mirror_side_key() {
        let s = Setup::from_toml(
            "[registers.7]\nradius = 0.4\norientation = 7\n[machine]\nmirror_swaps_comp_side = false\n",
        )
        .unwrap();
        assert_eq!(s.registers[&7].orientation, 7);
        assert_eq!(s.machine.mirror_swaps_comp_side, Some(false));
        assert_eq!(Setup::from_toml(&s.to_toml().unwrap()).unwrap(), s);
        assert_eq!(Setup::default().machine.mirror_swaps_comp_side, None);
        let e = Setup::from_toml("[registers.2]\norientation = 10\n").unwrap_err();
        assert!(e.to_string().contains("registers.2.orientation"), "{e}");
    }

    #[test]
    fn rejects_unknown_keys_and_offsets() {
        assert!(Setup::from_toml("[work_offsets]\nG60 = [0,0,0]\n").is_err());
        assert!(Setup::from_toml("[work_offsets]\n\"G54.1P49\" = [0,0,0]\n").is_err());
        assert!(Setup::from_toml("bogus = 1\n").is_err());
        assert!(Setup::from_toml("[machine]\nrapid_mm_per_min = -1\n").is_err());
    }

    #[test]
    fn values_out_of_range_are_refused_naming_the_key_and_the_range() {
        for (text, key) in [
            (
                "[machine]\nacceleration_mm_per_s2 = -1000\n",
                "machine.acceleration_mm_per_s2",
            ),
            (
                "[machine]\narc_tolerance_mm = -1\n",
                "machine.arc_tolerance_mm",
            ),
            (
                "[machine]\nrapid_mm_per_min = 0\n",
                "machine.rapid_mm_per_min",
            ),
            (
                "[machine]\nrapid_xyz_mm_per_min = [1e4, 0, 1e4]\n",
                "machine.rapid_xyz_mm_per_min",
            ),
            ("[machine]\nmax_work = 0\n", "machine.max_work"),
            (
                "[machine]\nmax_work = 100000000000000\n",
                "machine.max_work",
            ),
            ("[registers.3]\nradius = 1e300\n", "registers.3.radius"),
            ("[registers.3]\nlength = nan\n", "registers.3.length"),
            ("[work_offsets]\nG54 = [0, 1e300, 0]\n", "work_offsets.G54"),
            (
                "[machine]\ntravel_mm = [[0, 0, 0], [inf, 1, 1]]\n",
                "machine.travel_mm",
            ),
        ] {
            let e = Setup::from_toml(text).unwrap_err().to_string();
            assert!(e.contains(&format!("`{key}` must be from")), "{text}: {e}");
        }
        let e = Setup::from_toml("[machine]\nrapid_mm_per_min = 0\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "`machine.rapid_mm_per_min` must be from 1 to 10000000 (it is 0)"
        );
        // Zero acceleration (no ramps modelled) and tolerance stay allowed.
        assert!(
            Setup::from_toml("[machine]\nacceleration_mm_per_s2 = 0\narc_tolerance_mm = 0\n")
                .is_ok()
        );
    }
}
