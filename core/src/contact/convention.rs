//! Contact conventions: which engine's reading of the same contact law a material pair
//! follows. The same μs and μr mean different things in EDEM and in LIGGGHTS 3.8, so a
//! parameter set calibrated in one code does not carry over to the other unless the pair
//! speaks that code's dialect (`docs/conventions.md` compares every term).
//!
//! | convention | rolling torque | Coulomb test |
//! |---|---|---|
//! | [`RollingConvention::Edem`], [`FrictionConvention::Edem`] (default) | T_i = −μr·Fn·L_i·ω̂_i on each body, Fn the clipped total normal force, L_i the lever from body i's centre of mass (seed 000 eq. (7)) | \|spring + damping\| ≤ μs·Fn; the history is rescaled when the spring alone exceeds it |
//! | [`RollingConvention::LiggghtsEpsd2`] | M ← M + k_t·R*²·dt·ŵ_t, \|M\| ≤ μr·Fn·R*, T_j = −T_i = M, k_t = 8G*a, ŵ_t the tangent part of ω_i − ω_j, Fn the clipped total normal force (`rolling_model_epsd2.h`) | (rolling only; combine with either Coulomb test) |
//! | [`RollingConvention::LiggghtsCdt`], [`FrictionConvention::Liggghts`] | T_i = −T_j = −μr·F_el·R*·ŵ, ŵ the unit of ω_i − ω_j less its part along the normal, F_el = (4/3)E*·a·α, R* = R_iR_j/(R_i+R_j) (wall: R_i, ω_i) (`rolling_model_cdt.h`) | the spring alone: if St·\|δt\| > μs·Fn the force is the spring scaled to μs·Fn with no damping, else spring + damping, unbounded (`tangential_model_history.h`) |
//!
//! ```
//! use arachis_core::contact::{Conventions, FrictionConvention, RollingConvention};
//! let c: Conventions = "liggghts".parse().unwrap();
//! assert_eq!(c.rolling, RollingConvention::LiggghtsCdt);
//! assert_eq!(c.friction, FrictionConvention::Liggghts);
//! assert_eq!("edem".parse::<RollingConvention>(), Ok(RollingConvention::Edem));
//! assert!("lammps".parse::<RollingConvention>().is_err());
//! ```

use core::fmt;
use core::str::FromStr;

/// How the constant-directional-torque (CDT) rolling friction is read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RollingConvention {
    /// EDEM's standard rolling friction, seed 000 eq. (7): each body's own ω̂ and lever, the
    /// clipped total normal force, capped so it never reverses ω within a step
    /// ([`crate::contact::RollingCdt`]).
    #[default]
    Edem,
    /// LIGGGHTS 3.8's `rolling_friction cdt`: the relative spin, R*, the elastic normal force,
    /// no torsion part, equal and opposite torques, no cap
    /// ([`crate::contact::RollingCdtLiggghts`]).
    LiggghtsCdt,
    /// LIGGGHTS 3.8's `rolling_friction epsd2`: an incremental spring torque k_t·R*²·dt·ω_t on
    /// the relative spin, capped at μr·Fn·R*, equal and opposite, no dashpot
    /// ([`crate::contact::RollingEpsd2Liggghts`]). Needs an effect-history arena
    /// ([`crate::body::StorageLengths::with_effects`]) for the stored torque.
    LiggghtsEpsd2,
}

/// How the Coulomb limit bounds the tangential force.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FrictionConvention {
    /// EDEM's: the spring plus damping force is scaled onto μs·Fn, and the history is rescaled
    /// when the spring alone exceeds it ([`crate::contact::CoulombLimit`]).
    #[default]
    Edem,
    /// LIGGGHTS 3.8's `tangential history`: only the spring is tested against μs·Fn; a sliding
    /// contact has no tangential damping, a sticking one may exceed the limit by its damping.
    Liggghts,
}

/// The conventions of one material pair.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Conventions {
    /// Rolling friction.
    pub rolling: RollingConvention,
    /// Coulomb limit.
    pub friction: FrictionConvention,
}

impl Conventions {
    /// EDEM's conventions throughout (the default).
    pub const EDEM: Conventions = Conventions {
        rolling: RollingConvention::Edem,
        friction: FrictionConvention::Edem,
    };
    /// LIGGGHTS 3.8's conventions throughout (`tangential history rolling_friction cdt`).
    pub const LIGGGHTS: Conventions = Conventions {
        rolling: RollingConvention::LiggghtsCdt,
        friction: FrictionConvention::Liggghts,
    };

    /// `true` when every convention is EDEM's.
    pub fn is_edem(&self) -> bool {
        *self == Conventions::EDEM
    }
}

/// A convention name that is not known; carries the kind of convention asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownConvention {
    /// Which kind of convention: "rolling", "friction" or "contact".
    pub kind: &'static str,
    /// The names accepted.
    pub accepted: &'static str,
}

impl fmt::Display for UnknownConvention {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown {} convention (accepted: {})",
            self.kind, self.accepted
        )
    }
}

impl core::error::Error for UnknownConvention {}

impl RollingConvention {
    /// The name used in study files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            RollingConvention::Edem => "edem",
            RollingConvention::LiggghtsCdt => "liggghts-cdt",
            RollingConvention::LiggghtsEpsd2 => "liggghts-epsd2",
        }
    }
}

impl FrictionConvention {
    /// The name used in study files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            FrictionConvention::Edem => "edem",
            FrictionConvention::Liggghts => "liggghts",
        }
    }
}

impl FromStr for RollingConvention {
    type Err = UnknownConvention;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "edem" => Ok(RollingConvention::Edem),
            "liggghts-cdt" => Ok(RollingConvention::LiggghtsCdt),
            "liggghts-epsd2" => Ok(RollingConvention::LiggghtsEpsd2),
            _ => Err(UnknownConvention {
                kind: "rolling",
                accepted: "edem, liggghts-cdt, liggghts-epsd2",
            }),
        }
    }
}

impl FromStr for FrictionConvention {
    type Err = UnknownConvention;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "edem" => Ok(FrictionConvention::Edem),
            "liggghts" => Ok(FrictionConvention::Liggghts),
            _ => Err(UnknownConvention {
                kind: "friction",
                accepted: "edem, liggghts",
            }),
        }
    }
}

/// Both conventions of one engine by the engine's name: `edem` or `liggghts`.
impl FromStr for Conventions {
    type Err = UnknownConvention;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "edem" => Ok(Conventions::EDEM),
            "liggghts" => Ok(Conventions::LIGGGHTS),
            _ => Err(UnknownConvention {
                kind: "contact",
                accepted: "edem, liggghts",
            }),
        }
    }
}

impl fmt::Display for RollingConvention {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for FrictionConvention {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for r in [
            RollingConvention::Edem,
            RollingConvention::LiggghtsCdt,
            RollingConvention::LiggghtsEpsd2,
        ] {
            assert_eq!(r.name().parse::<RollingConvention>(), Ok(r));
        }
        for f in [FrictionConvention::Edem, FrictionConvention::Liggghts] {
            assert_eq!(f.name().parse::<FrictionConvention>(), Ok(f));
        }
        assert!(Conventions::default().is_edem());
        assert!(!Conventions::LIGGGHTS.is_edem());
        assert_eq!(
            "cdt".parse::<RollingConvention>().unwrap_err().accepted,
            "edem, liggghts-cdt, liggghts-epsd2"
        );
    }
}
