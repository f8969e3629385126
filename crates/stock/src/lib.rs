//! Stock simulation: a height field (mm, machine frame; each cell the lowest any tool reached) cut
//! along a [`swarf_toolpath::Toolpath`] by [`Simulation`] with a [`Stock`] and [`Tool`]s, read by
//! [`StockSetup`] from a [`swarf_interp::Setup`]; [`StockRun`] reports plowing and buried flutes.

mod field;
mod setup;
mod sim;

use serde::Deserialize;

pub use field::HeightField;
pub use setup::{StockRun, StockSetup, line_span};
pub use sim::{Finding, Simulation};

/// The finest cell a grid may have, in millimetres.
pub const MIN_CELL_MM: f64 = 0.005;

/// The most cells a grid may have along X or along Y.
pub const MAX_CELLS: usize = 4096;

/// About how many cells the default grid has along the stock's longer side.
pub const DEFAULT_CELLS: usize = 1024;

/// The largest coordinate or length accepted, in millimetres: past any machine, so an absurd
/// value is refused rather than computed.
pub const MAX_LENGTH: f64 = 1.0e6;

/// The block of material, an axis-aligned box in machine coordinates (`[stock]` in a setup).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stock {
    /// Lowest corner (X, Y, Z), mm.
    pub min: [f64; 3],
    /// Highest corner (X, Y, Z), mm.
    pub max: [f64; 3],
    /// Side of one square cell of the height field, mm; unset: the longer side over
    /// [`DEFAULT_CELLS`].
    pub cell_mm: Option<f64>,
}

impl Stock {
    /// The side of one cell and the number of cells along X and Y, once the corners and the
    /// cell are checked; the grid starts at `min` and may overhang `max` by part of a cell.
    pub fn grid(&self) -> Result<(f64, usize, usize), StockError> {
        for (key, corner) in [("stock.min", self.min), ("stock.max", self.max)] {
            for v in corner {
                in_range(key, v, -MAX_LENGTH, MAX_LENGTH)?;
            }
        }
        for (axis, name) in ['X', 'Y', 'Z'].into_iter().enumerate() {
            if self.max[axis] <= self.min[axis] {
                return Err(StockError::Empty { axis: name });
            }
        }
        let longer = (self.max[0] - self.min[0]).max(self.max[1] - self.min[1]);
        let finest = MIN_CELL_MM.max(longer / MAX_CELLS as f64);
        let cell = match self.cell_mm {
            Some(cell) => in_range("stock.cell_mm", cell, finest, longer)?,
            None => finest.max(longer / DEFAULT_CELLS as f64),
        };
        // The relative slack keeps a side that is a whole number of cells from gaining one.
        let cells = |axis: usize| {
            let n = ((self.max[axis] - self.min[axis]) / cell * (1.0 - 1e-9)).ceil();
            (n as usize).clamp(1, MAX_CELLS)
        };
        Ok((cell, cells(0), cells(1)))
    }
}

/// The form of a tool's cutting end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// Flat end mill.
    Flat,
    /// Ball end mill (a hemisphere of the tool's radius).
    Ball,
    /// Bull nose: a flat end with rounded corners of `corner_radius`.
    Bull {
        /// Radius of the corner rounding, mm (at most half the diameter).
        corner_radius: f64,
    },
    /// Drill: a cone of `point_angle_deg` up to the full diameter.
    Drill {
        /// Included angle of the point, degrees (118 unless set).
        point_angle_deg: f64,
    },
    /// Chamfer or spot mill: a cone of `point_angle_deg` up to the full diameter.
    Chamfer {
        /// Included angle of the point, degrees (90 unless set).
        point_angle_deg: f64,
    },
}

/// A cutting tool as the simulation sees it (`[tools.N]` in a setup).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(try_from = "ToolKeys")]
pub struct Tool {
    /// Cutting diameter, mm.
    pub diameter: f64,
    /// The cutting end.
    pub shape: Shape,
    /// Length of the flutes from the tip, mm: a feed that leaves material higher than this
    /// above the tip is a shank cut. Unset: not checked.
    pub flute_length: Option<f64>,
}

impl Default for Tool {
    /// The tool of a number the setup does not describe: a 10 mm flat end mill.
    fn default() -> Self {
        Tool {
            diameter: 10.0,
            shape: Shape::Flat,
            flute_length: None,
        }
    }
}

impl Tool {
    /// Checks every value of tool `number` against its range, naming `tools.N.key` when one is
    /// out.
    pub fn validate(&self, number: u32) -> Result<(), StockError> {
        let within = |name: &str, value: f64, min: f64, max: f64| {
            in_range(format_args!("tools.{number}.{name}"), value, min, max).map(drop)
        };
        within("diameter", self.diameter, 0.001, 1000.0)?;
        match self.shape {
            Shape::Flat | Shape::Ball => Ok(()),
            Shape::Bull { corner_radius } => {
                within("corner_radius", corner_radius, 0.0, self.diameter / 2.0)
            }
            Shape::Drill { point_angle_deg } | Shape::Chamfer { point_angle_deg } => {
                within("point_angle_deg", point_angle_deg, 1.0, 179.0)
            }
        }?;
        (self.flute_length).map_or(Ok(()), |f| within("flute_length", f, 0.001, MAX_LENGTH))
    }
}

/// The keys of `[tools.N]` as written, before the shape's own keys are sorted out.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ToolKeys {
    diameter: f64,
    #[serde(default)]
    shape: ShapeName,
    corner_radius: Option<f64>,
    point_angle_deg: Option<f64>,
    flute_length: Option<f64>,
}

#[derive(Deserialize, Default, PartialEq)]
#[serde(rename_all = "lowercase")]
enum ShapeName {
    #[default]
    Flat,
    Ball,
    Bull,
    Drill,
    Chamfer,
}

impl TryFrom<ToolKeys> for Tool {
    type Error = StockError;

    fn try_from(keys: ToolKeys) -> Result<Self, StockError> {
        let shape = match keys.shape {
            ShapeName::Flat => Shape::Flat,
            ShapeName::Ball => Shape::Ball,
            ShapeName::Bull => Shape::Bull {
                corner_radius: keys.corner_radius.ok_or(StockError::Shape(
                    "`corner_radius` is needed for shape = \"bull\"",
                ))?,
            },
            ShapeName::Drill => Shape::Drill {
                point_angle_deg: keys.point_angle_deg.unwrap_or(118.0),
            },
            ShapeName::Chamfer => Shape::Chamfer {
                point_angle_deg: keys.point_angle_deg.unwrap_or(90.0),
            },
        };
        if keys.corner_radius.is_some() && keys.shape != ShapeName::Bull {
            return Err(StockError::Shape(
                "`corner_radius` applies only to shape = \"bull\"",
            ));
        }
        if keys.point_angle_deg.is_some()
            && !matches!(keys.shape, ShapeName::Drill | ShapeName::Chamfer)
        {
            return Err(StockError::Shape(
                "`point_angle_deg` applies only to shape = \"drill\" or \"chamfer\"",
            ));
        }
        Ok(Tool {
            diameter: keys.diameter,
            shape,
            flute_length: keys.flute_length,
        })
    }
}

/// Why a stock or a tool was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StockError {
    /// A value outside the range its key allows (or not a number at all).
    #[error("`{key}` must be from {min} to {max} (it is {value})")]
    Range {
        /// The key, `stock.cell_mm` or `tools.3.diameter`.
        key: String,
        /// The lowest value allowed.
        min: f64,
        /// The highest value allowed.
        max: f64,
        /// The value given.
        value: f64,
    },
    /// A stock with no extent along an axis.
    #[error("`stock.max` must be above `stock.min` in {axis}")]
    Empty {
        /// The axis, `X`, `Y` or `Z`.
        axis: char,
    },
    /// A shape key missing or given to a shape it does not apply to.
    #[error("{0}")]
    Shape(&'static str),
    /// A setup's table that does not read as a stock or a tool (an unknown key, a missing one,
    /// a value of the wrong type).
    #[error("`[{key}]`: {message}")]
    Table {
        /// The table, `stock` or `tools.3`.
        key: String,
        /// What is wrong in it.
        message: String,
    },
}

/// `value` for `key` when it lies in `min..=max`; a range error naming the key otherwise.
fn in_range(
    key: impl std::fmt::Display,
    value: f64,
    min: f64,
    max: f64,
) -> Result<f64, StockError> {
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(StockError::Range {
            key: key.to_string(),
            min,
            max,
            value,
        })
    }
}
