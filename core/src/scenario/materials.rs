//! The materials and contact pairs of the bench bed (DESIGN §8), shared by every scenario so
//! that the digests exercise the calibrated peanut-pod parameters.

use crate::material::MaterialSpec;
use crate::pair::PairSpec;

/// Peanut pod: "ρ 582 kg/m³, E 8.43 MPa, ν 0.386" (DESIGN §8; seed 000 §3.1).
pub const POD: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 8.43e6,
    poisson: 0.386,
    density_kg_m3: 582.0,
};

/// 65Mn steel: "E 2.05e11 Pa, ν 0.3" (DESIGN §8), ρ 7865 kg/m³ (seed 000 Table 1).
pub const STEEL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 2.05e11,
    poisson: 0.3,
    density_kg_m3: 7865.0,
};

/// Pod–pod: "e 0.335, μs 0.854, μr 0.346" (DESIGN §8; seed 000 §3.6.2, calibrated).
pub const POD_POD: PairSpec = PairSpec {
    restitution: 0.335,
    friction: 0.854,
    rolling_friction: 0.346,
    conventions: crate::contact::Conventions::EDEM,
    terms: crate::pair::TermSwitches::ALL,
};

/// Pod–steel: "e 0.339, μs 0.589, μr 0.159" (DESIGN §8; seed 000 §3.4).
pub const POD_STEEL: PairSpec = PairSpec {
    restitution: 0.339,
    friction: 0.589,
    rolling_friction: 0.159,
    conventions: crate::contact::Conventions::EDEM,
    terms: crate::pair::TermSwitches::ALL,
};

/// Standard gravity along −z, m/s² (DESIGN §8: "gravity 9.81 m/s²").
pub const GRAVITY_M_S2: [f64; 3] = [0.0, 0.0, -crate::units::STANDARD_GRAVITY_M_S2];
