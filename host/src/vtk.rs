//! Particle frames as legacy VTK files that ParaView opens directly.
//!
//! Each frame is a `POLYDATA` file of vertices with point data: radius (m), velocity (m/s)
//! and body id. Frames named `frame_000123.vtk` are grouped by ParaView as a time series;
//! [`write_series`] also writes a `.pvd` collection carrying the simulated time of each frame.
//!
//! Exception to "use a library": the legacy VTK format is a few lines of text, and the
//! `vtkio` crate's stable release is no longer maintained, so we write it here.
//!
//! ```
//! use arachis::vtk::{ParticleFrame, write_frame};
//! let dir = tempfile::tempdir().unwrap();
//! let frame = ParticleFrame {
//!     time_s: 0.0,
//!     positions_m: vec![[0.0, 0.0, 0.004]],
//!     radii_m: vec![0.004],
//!     velocities_m_s: vec![[0.0, 0.0, -0.2]],
//!     body_ids: vec![0],
//! };
//! let path = dir.path().join("frame_000000.vtk");
//! write_frame(&path, &frame).unwrap();
//! assert!(std::fs::read_to_string(&path).unwrap().contains("POINTS 1 double"));
//! ```

use std::path::{Path, PathBuf};

use anyhow::{ensure, Context};
use arachis_core::prelude::*;
use arachis_core::units::{LENGTH_M_TO_MM, VELOCITY_M_S_TO_MM_MS};

use crate::io::write_atomic;

/// The state of every sphere at one instant, in SI units.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ParticleFrame {
    /// Simulated time of the frame, s.
    pub time_s: f64,
    /// Sphere centres, m.
    pub positions_m: Vec<[f64; 3]>,
    /// Sphere radii, m.
    pub radii_m: Vec<f64>,
    /// Sphere centre velocities, m/s.
    pub velocities_m_s: Vec<[f64; 3]>,
    /// The body (sphere or clump) each sphere belongs to.
    pub body_ids: Vec<u32>,
}

impl ParticleFrame {
    /// The spheres of `world` now, in SI units. A sphere's velocity is that of its centre,
    /// v + ω × r with r its offset from the body's centre of mass (exact for clump spheres).
    pub fn from_world<S: Scalar>(world: &World<'_, S>) -> Self {
        let bodies = world.bodies();
        let spheres = world.spheres();
        let mm_to_m = |v: [f64; 3]| v.map(|x| x / LENGTH_M_TO_MM);
        ParticleFrame {
            time_s: world.time_s(),
            positions_m: spheres
                .iter()
                .map(|s| mm_to_m(s.position.to_f64()))
                .collect(),
            radii_m: spheres.iter().map(|s| s.radius_m()).collect(),
            velocities_m_s: spheres
                .iter()
                .map(|s| {
                    let b = &bodies[s.body as usize];
                    let arm = s.position - b.position;
                    let v = (b.velocity + b.angular_velocity.cross(arm)).to_f64();
                    v.map(|x| x / VELOCITY_M_S_TO_MM_MS)
                })
                .collect(),
            body_ids: spheres.iter().map(|s| s.body).collect(),
        }
    }

    fn check(&self) -> anyhow::Result<()> {
        let n = self.positions_m.len();
        ensure!(
            self.radii_m.len() == n && self.velocities_m_s.len() == n && self.body_ids.len() == n,
            "VTK frame arrays differ in length: {} positions, {} radii, {} velocities, {} ids",
            n,
            self.radii_m.len(),
            self.velocities_m_s.len(),
            self.body_ids.len()
        );
        Ok(())
    }
}

/// Writes one frame to `path` as legacy ASCII VTK (atomically).
pub fn write_frame(path: &Path, frame: &ParticleFrame) -> anyhow::Result<()> {
    frame.check()?;
    write_atomic(path, |w| {
        let n = frame.positions_m.len();
        writeln!(w, "# vtk DataFile Version 3.0")?;
        writeln!(w, "Arachis particles t = {} s", frame.time_s)?;
        writeln!(w, "ASCII\nDATASET POLYDATA\nPOINTS {n} double")?;
        for p in &frame.positions_m {
            writeln!(w, "{} {} {}", p[0], p[1], p[2])?;
        }
        writeln!(w, "VERTICES {n} {}", 2 * n)?;
        for i in 0..n {
            writeln!(w, "1 {i}")?;
        }
        writeln!(
            w,
            "POINT_DATA {n}\nSCALARS radius_m double 1\nLOOKUP_TABLE default"
        )?;
        for r in &frame.radii_m {
            writeln!(w, "{r}")?;
        }
        writeln!(w, "SCALARS body_id int 1\nLOOKUP_TABLE default")?;
        for id in &frame.body_ids {
            writeln!(w, "{id}")?;
        }
        writeln!(w, "VECTORS velocity_m_s double")?;
        for v in &frame.velocities_m_s {
            writeln!(w, "{} {} {}", v[0], v[1], v[2])?;
        }
        Ok(())
    })
    .with_context(|| format!("cannot write VTK frame {}", path.display()))
}

/// Writes `frames` into `dir` as `frame_NNNNNN.vtk` plus `particles.pvd`, a ParaView
/// collection that maps each file to its simulated time. Returns the `.pvd` path.
pub fn write_series(dir: &Path, frames: &[ParticleFrame]) -> anyhow::Result<PathBuf> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create VTK directory {}", dir.display()))?;
    let mut entries = Vec::with_capacity(frames.len());
    for (i, frame) in frames.iter().enumerate() {
        let name = format!("frame_{i:06}.vtk");
        write_frame(&dir.join(&name), frame)?;
        entries.push((frame.time_s, name));
    }
    write_collection(dir, &entries)
}

/// Writes `dir/particles.pvd`, the ParaView collection of the frame files `entries`
/// (simulated time, s, and file name in `dir`), in their order. Returns its path.
pub fn write_collection(dir: &Path, entries: &[(f64, String)]) -> anyhow::Result<PathBuf> {
    let pvd = dir.join("particles.pvd");
    write_atomic(&pvd, |w| {
        writeln!(w, "<?xml version=\"1.0\"?>")?;
        writeln!(
            w,
            "<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>"
        )?;
        for (time_s, name) in entries {
            writeln!(
                w,
                "<DataSet timestep=\"{time_s}\" group=\"\" part=\"0\" file=\"{name}\"/>"
            )?;
        }
        writeln!(w, "</Collection>\n</VTKFile>")?;
        Ok(())
    })?;
    Ok(pvd)
}

/// VTK frames written one file at a time as a run goes (`frame_<step>.vtk`, named by step so
/// that a resumed run adds to the frames it took before), every `every` steps, with
/// [`StepFrames::collect`] writing the ParaView collection of the folder at the end.
#[derive(Debug, Clone, Copy)]
pub struct StepFrames<'a> {
    dir: &'a Path,
    every: u64,
}

impl<'a> StepFrames<'a> {
    /// Frames every `every` (≥ 1) steps into `dir`, which is created now, before the run.
    pub fn new(dir: &'a Path, every: u64) -> anyhow::Result<Self> {
        ensure!(every >= 1, "frames must be at least one step apart");
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create VTK directory {}", dir.display()))?;
        Ok(StepFrames { dir, every })
    }

    /// The file of the frame after `step` steps.
    fn name(step: u64) -> String {
        format!("frame_{step:09}.vtk")
    }

    /// Whether a frame falls after `step` steps.
    pub fn due(&self, step: u64) -> bool {
        step % self.every == 0
    }

    /// Steps from `step` to the next frame (≥ 1).
    pub fn steps_to_next(&self, step: u64) -> u64 {
        self.every - step % self.every
    }

    /// Writes the frame of `world` after `step` steps.
    pub fn take<S: Scalar>(&self, world: &World<'_, S>, step: u64) -> anyhow::Result<()> {
        write_frame(
            &self.dir.join(Self::name(step)),
            &ParticleFrame::from_world(world),
        )
    }

    /// Writes `particles.pvd`: every frame of the folder, in step order, each at its step's
    /// time (`dt_s` s a step). Returns its path.
    pub fn collect(&self, dt_s: f64) -> anyhow::Result<PathBuf> {
        let mut steps: Vec<u64> = std::fs::read_dir(self.dir)
            .with_context(|| format!("cannot list {}", self.dir.display()))?
            .filter_map(|e| {
                let name = e.ok()?.file_name().into_string().ok()?;
                name.strip_prefix("frame_")?
                    .strip_suffix(".vtk")?
                    .parse()
                    .ok()
            })
            .collect();
        steps.sort_unstable();
        let entries: Vec<(f64, String)> = steps
            .into_iter()
            .map(|s| (s as f64 * dt_s, Self::name(s)))
            .collect();
        write_collection(self.dir, &entries)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_spheres(time_s: f64) -> ParticleFrame {
        ParticleFrame {
            time_s,
            positions_m: vec![[0.0, 0.0, 0.004], [0.01, 0.0, 0.004]],
            radii_m: vec![0.004, 0.003],
            velocities_m_s: vec![[0.0, 0.0, 0.0], [0.0, 0.0, -0.2]],
            body_ids: vec![0, 1],
        }
    }

    #[test]
    fn frame_sections_have_consistent_counts() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.vtk");
        write_frame(&path, &two_spheres(0.5)).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let points = lines.iter().position(|l| *l == "POINTS 2 double").unwrap();
        assert_eq!(lines[points + 1], "0 0 0.004");
        assert_eq!(lines[points + 3], "VERTICES 2 4");
        assert!(text.contains("SCALARS radius_m double 1\nLOOKUP_TABLE default\n0.004\n0.003\n"));
        assert!(text.ends_with("VECTORS velocity_m_s double\n0 0 0\n0 0 -0.2\n"));
    }

    #[test]
    fn mismatched_arrays_are_an_error_and_write_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.vtk");
        let mut frame = two_spheres(0.0);
        frame.radii_m.pop();
        assert!(write_frame(&path, &frame).is_err());
        assert!(!path.exists());
    }

    #[test]
    fn series_lists_every_frame_with_its_time() {
        let dir = tempfile::tempdir().unwrap();
        let pvd = write_series(dir.path(), &[two_spheres(0.0), two_spheres(0.25)]).unwrap();
        let text = std::fs::read_to_string(pvd).unwrap();
        assert!(text.contains("timestep=\"0.25\" group=\"\" part=\"0\" file=\"frame_000001.vtk\""));
        assert!(dir.path().join("frame_000001.vtk").exists());
    }
}
