//! `arachis field FILE [--seed N] [--steps K] [--vtk FILE.vtk] [--picture FILE.svg]`: lay out
//! the field of a field file (`crate::field`: the plants of its variety in ridge rows, their
//! pods in a bed of soil grains), put it in one world, step it K steps (0: none) and print
//! one JSON line: plants, pods, grains, bonds, where the pods lie, the time step and the
//! world's digest. `--vtk` writes every sphere for ParaView, `--picture` the plan view of the
//! plants. A bad field or variety file is refused with its path, line and key; nothing is
//! written.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use arachis_core::prelude::*;
use arachis_core::units::LENGTH_M_TO_MM;
use serde::Serialize;

use crate::arena::{OwnedBonds, OwnedStorage};
use crate::field::picture::write_field_picture;
use crate::field::soil::fill_fraction;
use crate::field::FieldSpec;
use crate::vtk::{write_frame, ParticleFrame};

/// Arguments of `arachis field`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Field file (TOML, see `arachis::field`).
    pub file: PathBuf,
    /// Seed of the layout (plants, their turns, the grains).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Steps to run (gravity, cohesion, contacts between plants).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u64).range(0..=MAX_STEPS))]
    pub steps: u64,
    /// Write every sphere after the steps as legacy VTK (ParaView).
    #[arg(long, value_name = "FILE.vtk")]
    pub vtk: Option<PathBuf>,
    /// Write the plan view of the laid-out field (plants from above), SVG.
    #[arg(long, value_name = "FILE.svg")]
    pub picture: Option<PathBuf>,
}

/// Most steps one call runs.
const MAX_STEPS: u64 = 100_000_000;

/// The printed line.
#[derive(Debug, Serialize)]
struct FieldLine {
    name: String,
    seed: u64,
    plants: usize,
    pods: usize,
    grains: usize,
    spheres: usize,
    bonds: usize,
    /// Fraction of the bed the grains fill.
    soil_fill_fraction: f64,
    bed_min_m: [f64; 3],
    bed_max_m: [f64; 3],
    /// Pods whose centre lies inside the bed (below the surface, within its sides).
    pods_in_bed: usize,
    /// Shallowest and deepest pod centre below the surface, mm.
    pod_depth_mm: [f64; 2],
    dt_s: f64,
    steps: u64,
    simulated_s: f64,
    wall_seconds: f64,
    threads: usize,
    digest: String,
}

/// Runs `arachis field`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let spec = FieldSpec::read(&args.file)?;
    let field = spec
        .plant(args.seed)
        .with_context(|| format!("{}: cannot lay out the field", args.file.display()))?;
    let mut arena = OwnedStorage::<Fx>::new(field.storage_lengths(&spec));
    let mut bonds = OwnedBonds::<Fx>::new(field.bond_count());
    let mut world = World::new(arena.storage()).map_err(|e| anyhow::anyhow!("{e}"))?;
    world
        .attach_bond_storage(bonds.storage())
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let loaded = field.load_into(&spec, &mut world).map_err(|e| {
        anyhow::anyhow!(
            "{}: cannot build the field's world: {e}",
            args.file.display()
        )
    })?;
    let started = Instant::now();
    crate::stepping::run(&mut world, args.steps).map_err(|e| {
        anyhow::anyhow!(
            "{}: step failed at t = {} s: {e}",
            args.file.display(),
            world.time_s()
        )
    })?;
    let wall_seconds = started.elapsed().as_secs_f64();
    let pod_z_mm: Vec<f64> = loaded
        .pods
        .iter()
        .map(|&id| world.body(id).position.to_f64()[2])
        .collect();
    let pods_in_bed = loaded
        .pods
        .iter()
        .filter(|&&id| {
            let p = world.body(id).position.to_f64().map(|x| x / LENGTH_M_TO_MM);
            (0..3).all(|k| (field.bed_min_m[k]..=field.bed_max_m[k]).contains(&p[k]))
        })
        .count();
    let line = FieldLine {
        name: spec.field.name.clone(),
        seed: args.seed,
        plants: field.plants.len(),
        pods: field.pods(),
        grains: field.grains.len(),
        spheres: field.spheres(),
        bonds: field.bond_count(),
        soil_fill_fraction: fill_fraction(&field.grains, field.bed_min_m, field.bed_max_m),
        bed_min_m: field.bed_min_m,
        bed_max_m: field.bed_max_m,
        pods_in_bed,
        pod_depth_mm: [
            -pod_z_mm.iter().copied().fold(f64::MIN, f64::max),
            -pod_z_mm.iter().copied().fold(f64::MAX, f64::min),
        ],
        dt_s: world.timestep_s(),
        steps: args.steps,
        simulated_s: world.time_s(),
        wall_seconds,
        threads: crate::stepping::run_threads(),
        digest: format!("{:016x}", world.digest()),
    };
    if let Some(path) = &args.vtk {
        write_frame(path, &ParticleFrame::from_world(&world))?;
    }
    if let Some(path) = &args.picture {
        let title = format!("{}, seed {}", spec.field.name, args.seed);
        write_field_picture(path, &field, &title)?;
    }
    println!("{}", serde_json::to_string(&line)?);
    Ok(())
}
