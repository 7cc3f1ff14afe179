//! The model's parameters as the diagnosis loop sees them: the **base** parameters a study's
//! calibration sets (and a fit may move), and the optional **effects**, each off at 0 —
//! both as the study's rigs declare them ([`crate::rigs::parameter::RigParameter`], with their
//! units and finite-difference steps). Values live in a [`ParameterValues`] map by key.

use anyhow::{bail, Result};

use crate::calibration::ParameterValues;
pub use crate::rigs::parameter::{RigParameter as ParamInfo, Role};

/// The value of `info` in `p` (0 when absent: an effect that is off).
pub fn value(info: &ParamInfo, p: &ParameterValues) -> f64 {
    p.get(info.key).copied().unwrap_or(0.0)
}

/// Sets `info` to `v` in `p`.
pub fn set(info: &ParamInfo, p: &mut ParameterValues, v: f64) {
    p.insert(info.key.to_owned(), v);
}

/// The closed interval [lo, hi] a fit and a finite difference may move `info` in: its
/// physical limits, where an open end (e > 0, E > 0, ν < 0.5) is moved inwards by one
/// finite-difference step, since no value on it is admissible. A closed end (e = 1, an effect
/// at 0) is part of the interval: an estimate may sit on it.
pub fn interval(info: &ParamInfo) -> (f64, f64) {
    let (lo, hi) = info.limits.ends();
    let inwards = |end: crate::limits::End, sign: f64| {
        if end.closed || end.value.is_infinite() {
            end.value
        } else {
            end.value + sign * info.fd_step
        }
    };
    (inwards(lo, 1.0), inwards(hi, -1.0))
}

/// The parameters of a diagnosis: those of its rigs.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Catalogue(pub Vec<&'static ParamInfo>);

impl Catalogue {
    /// Every parameter the rigs named `rigs` declare, each once, in catalogue order.
    pub fn of_rigs<'a>(rigs: impl IntoIterator<Item = &'a str>) -> Self {
        let mut all: Vec<&'static ParamInfo> = Vec::new();
        for name in rigs {
            for p in crate::rigs::catalogue::find(name)
                .map(|k| k.parameters)
                .unwrap_or_default()
            {
                if all.iter().all(|q| q.key != p.key) {
                    all.push(p);
                }
            }
        }
        Self(all)
    }

    /// Look a parameter up by name; the error lists the known names.
    pub fn param(&self, name: &str) -> Result<&'static ParamInfo> {
        match self.0.iter().find(|p| p.name == name) {
            Some(p) => Ok(p),
            None => bail!(
                "unknown parameter or effect '{name}'; known: {}",
                self.0.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
            ),
        }
    }

    /// Look an effect up by name (refuses base parameters).
    pub fn effect(&self, name: &str) -> Result<&'static ParamInfo> {
        let p = self.param(name)?;
        if p.role != Role::Effect {
            bail!(
                "'{name}' is a base parameter, not an optional effect; effects: {}",
                self.effects()
                    .map(|p| p.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        Ok(p)
    }

    /// The base parameters.
    pub fn base(&self) -> impl Iterator<Item = &'static ParamInfo> + '_ {
        self.0.iter().copied().filter(|p| p.role == Role::Base)
    }

    /// The candidate effects.
    pub fn effects(&self) -> impl Iterator<Item = &'static ParamInfo> + '_ {
        self.0.iter().copied().filter(|p| p.role == Role::Effect)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rigs::single_sphere::PARAMETERS;

    #[test]
    fn open_ends_move_in_by_one_step_and_closed_ends_stay() {
        let by_name = |n: &str| PARAMETERS.iter().find(|p| p.name == n).unwrap();
        // e ∈ (0, 1]: 0 is not admissible, 1 is.
        assert_eq!(interval(by_name("restitution")), (0.01, 1.0));
        // E > 0, unbounded above.
        assert_eq!(interval(by_name("youngs_modulus")), (2.0e5, f64::INFINITY));
        // An effect is off at 0, which is admissible.
        assert_eq!(interval(by_name("cohesion")), (0.0, f64::INFINITY));
        // The plastic fraction λ < 1.
        assert_eq!(interval(by_name("hysteretic")), (0.0, 0.98));
    }
}
