//! A watch on a field's speeds: the fastest free body of the run, and the first time a body
//! moved faster than anything in the field can make it move (a runaway).
//!
//! **Why.** Nothing in a field is driven faster than the machine's fastest part, and a free
//! body hit by a heavy part leaves it at most twice that part's speed (an elastic bounce off
//! an infinite mass); gravity adds the speed of a fall from the plants' height, a few m/s.
//! A body faster than [`SpeedWatch::bound_m_s`] took its energy from the numerics (a time
//! step too long for a stiff contact or bond, a long step of the soil's multi-rate cycle), so
//! its path and whatever it hit are wrong, and a few such bodies make the neighbour list
//! rebuild every few steps. The watch says so, with the body and the step, instead of leaving
//! it to a look at a VTK frame (issue 20: stalk spheres at 100 m/s, `core/API_NOTES.md`).
//!
//! ```
//! use arachis::field::speed_watch::{Fastest, SpeedWatch};
//! let mut watch = SpeedWatch::new(2.0);
//! assert_eq!(watch.bound_m_s(), 5.0); // the fall floor: 2 × 2 m/s is less
//! watch.note(Fastest { step: 250, body: 7, speed_m_s: 3.0, position_m: [0.0; 3] });
//! assert!(watch.first_runaway().is_none());
//! watch.note(Fastest { step: 500, body: 9, speed_m_s: 6.0, position_m: [0.0; 3] });
//! assert_eq!(watch.first_runaway().map(|f| f.body), Some(9));
//! assert_eq!(watch.fastest().map(|f| f.speed_m_s), Some(6.0));
//! ```

use arachis_core::prelude::*;
use arachis_core::units::LENGTH_M_TO_MM;
use glam::DVec3;
use serde::Serialize;

/// The speed a free body reaches in any field without a machine, m/s: a fall of about
/// 1.3 m (sqrt(2·9.81·1.3) = 5.05 m/s), several times a plant's height (seed 000: main stem
/// 45.3 cm, lateral branches 54.1 cm).
pub const FALL_SPEED_FLOOR_M_S: f64 = 5.0;

/// How many times its speed a heavy moving part can give a free body: an elastic bounce off
/// an infinite mass leaves at twice the wall's speed.
pub const BOUNCE_SPEED_FACTOR: f64 = 2.0;

/// The fastest free body at one moment of a run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fastest {
    /// Steps done when it was seen.
    pub step: u64,
    /// Its body id.
    pub body: u32,
    /// Its speed, m/s.
    pub speed_m_s: f64,
    /// Its centre, m.
    pub position_m: [f64; 3],
}

/// The fastest free body of a run so far and the first runaway.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedWatch {
    bound_m_s: f64,
    fastest: Option<Fastest>,
    first_runaway: Option<Fastest>,
}

impl SpeedWatch {
    /// A watch for a field whose fastest driven part moves at `fastest_part_m_s` (0 without
    /// a machine): its bound is the larger of [`BOUNCE_SPEED_FACTOR`] × that speed and
    /// [`FALL_SPEED_FLOOR_M_S`].
    pub fn new(fastest_part_m_s: f64) -> Self {
        SpeedWatch {
            bound_m_s: (BOUNCE_SPEED_FACTOR * fastest_part_m_s).max(FALL_SPEED_FLOOR_M_S),
            fastest: None,
            first_runaway: None,
        }
    }

    /// The speed above which a free body is a runaway, m/s.
    pub fn bound_m_s(&self) -> f64 {
        self.bound_m_s
    }

    /// The fastest body seen so far.
    pub fn fastest(&self) -> Option<Fastest> {
        self.fastest
    }

    /// The first body seen faster than the bound.
    pub fn first_runaway(&self) -> Option<Fastest> {
        self.first_runaway
    }

    /// Takes note of the fastest body at one moment; returns it if it is the run's first
    /// runaway.
    pub fn note(&mut self, now: Fastest) -> Option<Fastest> {
        if self.fastest.is_none_or(|f| now.speed_m_s > f.speed_m_s) {
            self.fastest = Some(now);
        }
        if self.first_runaway.is_none() && now.speed_m_s > self.bound_m_s {
            self.first_runaway = Some(now);
            return Some(now);
        }
        None
    }

    /// Looks at `world` after `step` steps ([`fastest_free_body`]) and takes note.
    pub fn observe<S: Scalar>(&mut self, world: &World<'_, S>, step: u64) -> Option<Fastest> {
        fastest_free_body(world, step).and_then(|f| self.note(f))
    }
}

/// The fastest body that forces move (kinematic bodies, whose inverse mass is zero, are
/// driven and not counted), or `None` if there is none.
pub fn fastest_free_body<S: Scalar>(world: &World<'_, S>, step: u64) -> Option<Fastest> {
    world
        .bodies()
        .iter()
        .enumerate()
        .filter(|(_, b)| b.inv_mass != S::ZERO)
        .map(|(i, b)| (i, DVec3::from(b.velocity.to_f64()).length(), b))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, speed_m_s, b)| Fastest {
            step,
            body: i as u32,
            // Velocities are in mm/ms = m/s.
            speed_m_s,
            position_m: b.position.to_f64().map(|x| x / LENGTH_M_TO_MM),
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use arachis_core::scenario::materials::POD;

    #[test]
    fn the_bound_is_the_bounce_or_the_fall() {
        assert_eq!(SpeedWatch::new(0.0).bound_m_s(), FALL_SPEED_FLOOR_M_S);
        assert_eq!(SpeedWatch::new(9.84).bound_m_s(), 2.0 * 9.84);
    }

    #[test]
    fn the_fastest_free_body_is_found_and_kinematic_ones_are_passed_over() {
        let lengths = StorageLengths::for_spheres(3, 3);
        let mut storage = arachis_core::owned::OwnedStorage::<Fx>::new(lengths);
        let mut w = World::new(storage.storage()).unwrap();
        let m = w.add_material(POD).unwrap();
        let at = |x: f64, v: f64| SphereSpec {
            velocity_m_s: [0.0, v, 0.0],
            ..SphereSpec::at_rest(m, 0.004, [x, 0.0, 0.0])
        };
        w.add_sphere(at(0.0, 1.0)).unwrap();
        w.add_sphere(at(0.1, 3.0)).unwrap();
        let driven = w.add_sphere(at(0.2, 50.0)).unwrap();
        w.set_body_kinematic(driven).unwrap();
        let f = fastest_free_body(&w, 12).unwrap();
        assert_eq!((f.step, f.body), (12, 1));
        // 3 m/s to the rounding of the fixed point's velocity (2^-32 mm/ms).
        assert!((f.speed_m_s - 3.0).abs() < 1e-9, "{}", f.speed_m_s);
        assert!((f.position_m[0] - 0.1).abs() < 1e-9);
    }
}
