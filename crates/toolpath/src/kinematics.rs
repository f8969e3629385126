//! The machine's motion limits and the trapezoidal velocity profile timed with them.

use glam::DVec3;
use swarf_interp::Machine;

/// The machine's motion limits used by the time model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Speed along the path of a rapid move, mm/s.
    pub rapid_mm_per_s: f64,
    /// Rapid rate of each axis X, Y, Z in mm/s (infinite where an axis sets no limit of its own).
    pub rapid_axes_mm_per_s: DVec3,
    /// Path acceleration and deceleration in mm/s² (infinite: none modelled).
    pub acceleration_mm_per_s2: f64,
}

impl Default for Kinematics {
    fn default() -> Self {
        Kinematics::from_machine(&Machine::default())
    }
}

impl Kinematics {
    /// The limits given by a setup's `[machine]` section. A rate that is not a positive
    /// finite number falls back to the path rapid rate (10 m/min when that is invalid too);
    /// an acceleration that is not positive and finite means none is modelled.
    pub fn from_machine(machine: &Machine) -> Self {
        let rapid = positive(machine.rapid_mm_per_min).unwrap_or(10_000.0);
        let axes = machine
            .rapid_xyz_mm_per_min
            .map_or([f64::INFINITY; 3], |rates| {
                rates.map(|r| positive(r).unwrap_or(f64::INFINITY))
            });
        Kinematics {
            rapid_mm_per_s: rapid / 60.0,
            rapid_axes_mm_per_s: DVec3::from_array(axes) / 60.0,
            acceleration_mm_per_s2: positive(machine.acceleration_mm_per_s2)
                .unwrap_or(f64::INFINITY),
        }
    }

    /// Speed along the path of a rapid in unit `direction`: the path rapid rate, lowered so
    /// that no axis exceeds its own rate.
    pub fn rapid_speed(&self, direction: DVec3) -> f64 {
        (0..3).fold(self.rapid_mm_per_s, |v, k| {
            let share = direction[k].abs();
            if share > 1e-12 {
                v.min(self.rapid_axes_mm_per_s[k] / share)
            } else {
                v
            }
        })
    }

    /// One over the acceleration, which [`Kinematics::move_secs_per`] takes: worked out once
    /// for a run of moves rather than a division each.
    pub(crate) fn per_acceleration(&self) -> f64 {
        1.0 / self.acceleration_mm_per_s2
    }

    /// Seconds for `length` mm on a trapezoid from `entry` up to `cruise` and down to `exit`
    /// (mm/s), `per_a` from [`Kinematics::per_acceleration`]; zero if empty or `cruise <= 0`.
    #[inline]
    pub(crate) fn move_secs_per(
        &self,
        length: f64,
        cruise: f64,
        entry: f64,
        exit: f64,
        per_a: f64,
    ) -> f64 {
        if length <= 0.0 || cruise.is_nan() || cruise <= 0.0 {
            return 0.0;
        }
        let a = self.acceleration_mm_per_s2;
        if a.is_infinite() {
            return length / cruise;
        }
        let u = entry.clamp(0.0, cruise);
        let w = exit.clamp(0.0, cruise);
        // A move through both joins at its feed (most of a smooth run) is all steady, as below:
        // the peak is the feed (the root of at least its square, where that square does not
        // underflow), the ramps take 0 · `per_a` (0 where that is finite) and the steady part
        // is `length.max(0.0)`.
        if per_a.is_finite() && cruise > 1e-100 && u == cruise && w == cruise {
            return length.max(0.0) / cruise;
        }
        let squared = (2.0 * a * length + u * u + w * w) / 2.0;
        // Without the square root where the move clearly reaches its feed (as in
        // `reach_capped`): the passes time every move, and square roots and divisions take
        // turns on one unit of the processor.
        let peak = if root_clearly_reaches(squared, cruise) {
            cruise
        } else {
            let peak = squared.sqrt();
            if peak < cruise {
                // Short of its feed, the move speeds up and slows down over its whole length,
                // with no steady part but the roundings of the two lengths (a few ulps of it):
                // the division that would time that part is spared.
                return ((peak - u).max(0.0) + (peak - w).max(0.0)) * per_a;
            }
            cruise
        };
        let speed_up = ((peak * peak - u * u) * (0.5 * per_a)).max(0.0);
        let slow_down = ((peak * peak - w * w) * (0.5 * per_a)).max(0.0);
        let steady = (length - speed_up - slow_down).max(0.0);
        ((peak - u).max(0.0) + (peak - w).max(0.0)) * per_a + steady / peak
    }

    /// The highest speed reachable after `length` mm starting at `speed`.
    pub(crate) fn reach(&self, speed: f64, length: f64) -> f64 {
        if length <= 0.0 {
            speed
        } else {
            (speed * speed + 2.0 * self.acceleration_mm_per_s2 * length).sqrt()
        }
    }

    /// `cap.min(self.reach(speed, length))` bit for bit, without the square root where the
    /// reachable speed is clearly above the cap (most joins of a long run at one feed): the
    /// planner's passes chain these, and a chain of square roots waits on each in turn.
    #[inline]
    pub(crate) fn reach_capped(&self, speed: f64, length: f64, cap: f64) -> f64 {
        if length > 0.0
            && root_clearly_reaches(
                speed * speed + 2.0 * self.acceleration_mm_per_s2 * length,
                cap,
            )
        {
            return cap;
        }
        cap.min(self.reach(speed, length))
    }
}

/// Whether the rounded square root of `squared` is surely at least `cap`, told without taking
/// it: the margin covers the roundings of cap² and of the root. False for a cap so small that
/// its square would underflow, where only the root itself can tell.
#[inline]
fn root_clearly_reaches(squared: f64, cap: f64) -> bool {
    cap > 1e-100 && squared >= cap * cap * (1.0 + 4.0 * f64::EPSILON)
}

fn positive(v: f64) -> Option<f64> {
    (v.is_finite() && v > 0.0).then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xorshift;

    /// A speed, length or feed for the tests of the model's arithmetic, from the random `r`: one
    /// in eight an edge value (zeros, the smallest and largest, infinity, NaN, a negative one),
    /// else a random magnitude around the speeds and lengths of real moves.
    fn edge_or_random(r: u64) -> f64 {
        const EDGES: [f64; 11] = [
            0.0,
            -0.0,
            1e-300,
            1e-100,
            1.0,
            5.0,
            16.666_666_666_666_668,
            1e154,
            f64::INFINITY,
            f64::NAN,
            -1.0,
        ];
        if r.is_multiple_of(8) {
            EDGES[(r / 8 % EDGES.len() as u64) as usize]
        } else {
            let scale = 10f64.powi((r % 13) as i32 - 6);
            scale * (r >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn capped_reach_is_the_plain_one_bit_for_bit() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut value = move || edge_or_random(xorshift(&mut seed));
        for acceleration in [500.0, 1e-3, 1e9, f64::INFINITY] {
            let k = Kinematics {
                acceleration_mm_per_s2: acceleration,
                ..Kinematics::default()
            };
            for _ in 0..200_000 {
                let (speed, length, cap) = (value(), value(), value());
                let want = cap.min(k.reach(speed, length));
                let got = k.reach_capped(speed, length, cap);
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "speed {speed} length {length} cap {cap} acceleration {acceleration}"
                );
            }
            // Right at the cap: the root lands on it, just under or just over.
            for i in 0..10_000 {
                let cap = 1.0 + f64::from(i) * 1e-3;
                let length = 0.25;
                let speed = (cap * cap - 2.0 * acceleration.min(1e3) * length)
                    .max(0.0)
                    .sqrt();
                let want = cap.min(k.reach(speed, length));
                assert_eq!(k.reach_capped(speed, length, cap).to_bits(), want.to_bits());
            }
        }
    }

    /// [`Kinematics::move_secs_per`] as written before it spared the square root of a move
    /// that reaches its feed and the division of one that does not.
    fn plain_move_secs(k: &Kinematics, length: f64, cruise: f64, entry: f64, exit: f64) -> f64 {
        if length <= 0.0 || cruise.is_nan() || cruise <= 0.0 {
            return 0.0;
        }
        let a = k.acceleration_mm_per_s2;
        if a.is_infinite() {
            return length / cruise;
        }
        let per_a = k.per_acceleration();
        let u = entry.clamp(0.0, cruise);
        let w = exit.clamp(0.0, cruise);
        let peak = cruise.min(((2.0 * a * length + u * u + w * w) / 2.0).sqrt());
        let speed_up = ((peak * peak - u * u) * (0.5 * per_a)).max(0.0);
        let slow_down = ((peak * peak - w * w) * (0.5 * per_a)).max(0.0);
        let steady = (length - speed_up - slow_down).max(0.0);
        ((peak - u).max(0.0) + (peak - w).max(0.0)) * per_a + steady / peak
    }

    /// `got` is `want` to the bit where the move reaches its feed, and where it does not, no
    /// more than the steady part the shortcut leaves out: the roundings of the lengths over
    /// which the move speeds up and slows down, a few ulps of the squared speeds over `a`.
    fn same_move_time(k: &Kinematics, length: f64, cruise: f64, entry: f64, exit: f64, got: f64) {
        let want = plain_move_secs(k, length, cruise, entry, exit);
        let a = k.acceleration_mm_per_s2;
        let timed = length > 0.0 && cruise > 0.0 && a.is_finite();
        let (u, w) = (
            entry.clamp(0.0, cruise.max(0.0)),
            exit.clamp(0.0, cruise.max(0.0)),
        );
        let squared = (2.0 * a * length + u * u + w * w) / 2.0;
        let short_of_feed = timed && squared.sqrt() < cruise;
        if short_of_feed && want.is_finite() {
            let noise = 16.0 * f64::EPSILON * squared / (a * squared.sqrt());
            assert!(
                got <= want && want - got <= 1e-12 * want + noise,
                "length {length} cruise {cruise} entry {entry} exit {exit} a {a}: {got} {want}"
            );
        } else {
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "length {length} cruise {cruise} entry {entry} exit {exit} a {a}"
            );
        }
    }

    #[test]
    fn a_move_is_timed_as_with_the_square_root_and_the_division() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut value = move || edge_or_random(xorshift(&mut seed));
        for acceleration in [1000.0, 500.0, 1e-3, 1e9, f64::INFINITY] {
            let k = Kinematics {
                acceleration_mm_per_s2: acceleration,
                ..Kinematics::default()
            };
            let per_a = k.per_acceleration();
            for _ in 0..200_000 {
                let (length, cruise, entry, exit) = (value(), value(), value(), value());
                let got = k.move_secs_per(length, cruise, entry, exit, per_a);
                same_move_time(&k, length, cruise, entry, exit, got);
            }
            // Right at the feed: the peak speed's root lands on it, just under or just over.
            for i in 0..10_000 {
                let cruise = 1.0 + f64::from(i) * 1e-3;
                let entry = 0.5 * cruise;
                // Where (2aL + u² + w²) / 2 is the feed squared.
                let length = (cruise * cruise - entry * entry) / acceleration.min(1e12);
                let length = length * (1.0 + f64::from(i % 7) * f64::EPSILON - 3.0 * f64::EPSILON);
                let got = k.move_secs_per(length, cruise, entry, entry, per_a);
                same_move_time(&k, length, cruise, entry, entry, got);
            }
        }
        // A move so short that 2aL underflows to zero, from rest to rest: it takes no time
        // (2·sqrt(L/a) is about 1e-160 s), not the endless time its zero peak speed gives.
        let k = Kinematics {
            acceleration_mm_per_s2: 1e-3,
            ..Kinematics::default()
        };
        for (entry, exit) in [(0.0, 0.0), (-1.0, 0.0), (0.0, -0.0)] {
            let got = k.move_secs_per(5e-324, 1.0, entry, exit, k.per_acceleration());
            assert!((0.0..1e-150).contains(&got), "{entry} {exit}: {got}");
        }
    }

    /// A move through both joins at its feed is timed as all steady, to the bit of the plain
    /// formula: feeds and lengths over their whole ranges, the move's own ramps negligible or
    /// not, and accelerations down to a subnormal one (whose moves take no finite time).
    #[test]
    fn a_move_at_its_feed_throughout_is_timed_as_the_plain_formula() {
        let mut seed = 0x5851_f42d_4c95_7f2d_u64;
        let mut magnitude = move |least: i32, most: i32| {
            let r = xorshift(&mut seed);
            let exponent = least + (r % (most - least + 1) as u64) as i32;
            (1.0 + (r >> 11) as f64 / (1u64 << 53) as f64) * 10f64.powi(exponent)
        };
        for acceleration in [1000.0, 1e-3, 1e9, 1e-310, f64::INFINITY] {
            let k = Kinematics {
                acceleration_mm_per_s2: acceleration,
                ..Kinematics::default()
            };
            for _ in 0..50_000 {
                let (cruise, length) = (magnitude(-99, 150), magnitude(-300, 6));
                for (entry, exit) in [(cruise, cruise), (2.0 * cruise, f64::INFINITY)] {
                    let got = k.move_secs_per(length, cruise, entry, exit, k.per_acceleration());
                    let want = plain_move_secs(&k, length, cruise, entry, exit);
                    assert_eq!(
                        got.to_bits(),
                        want.to_bits(),
                        "length {length} cruise {cruise} a {acceleration}"
                    );
                }
            }
        }
    }
}
