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
