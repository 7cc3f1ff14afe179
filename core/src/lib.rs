//! Arachis core: a `no_std`, allocation-free, fixed-point DEM core.
//!
//! (Crate documentation is written with the modules; see issue 2.)
#![no_std]
#![deny(missing_docs)]

pub mod scenario;
