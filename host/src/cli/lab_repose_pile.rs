//! `arachis lab repose-pile DUMP`: the repose angle of a pile of spheres from its final
//! positions, photographed exactly as the repose rig photographs its own pile (12 side views
//! over a half turn, 4 pixels per radius of the smallest sphere, the `lab repose` contour and
//! flank fits; `rigs::repose_cylinder::photograph`). It reads another engine's result, so
//! both engines' piles are measured by one extraction: the LIGGGHTS cross-check
//! (`scripts/cross-check-repose.sh`) runs it on the dump that `arachis export liggghts`'s
//! deck writes.
//!
//! The input is a LAMMPS/LIGGGHTS text dump (`write_dump all custom FILE id radius x y z`):
//! after a line `ITEM: ATOMS` naming the columns, one sphere per line; columns `radius`,
//! `x`, `y`, `z` in metres (`units si`), any others ignored. The floor is z = 0.
//!
//! ```text
//! arachis lab repose-pile final.dump            # the angle and its views
//! arachis lab --json repose-pile final.dump     # one JSON object
//! ```

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use arachis_core::units::LENGTH_M_TO_MM;
use serde::Serialize;

use crate::repose::{SimulatedRepose, Sphere};
use crate::rigs::repose_cylinder::photograph;

/// Arguments of `arachis lab repose-pile`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The final positions: a LIGGGHTS/LAMMPS text dump with columns radius, x, y, z in
    /// metres (`write_dump all custom FILE id radius x y z`).
    pub dump: PathBuf,
}

/// The JSON output.
#[derive(Debug, Serialize)]
struct Report<'a> {
    dump: String,
    spheres: usize,
    mm_per_px: f64,
    /// Views left out (azimuth, degrees; reason), as the rig leaves them out.
    refused_views: &'a [(f64, String)],
    #[serde(flatten)]
    measurement: &'a SimulatedRepose,
}

/// Runs `arachis lab repose-pile`, printing to standard output.
pub fn run(args: Args, json: bool) -> anyhow::Result<()> {
    execute(args, json, &mut std::io::stdout().lock())
}

/// Runs `arachis lab repose-pile`, printing to `out`.
pub fn execute(args: Args, json: bool, out: &mut dyn Write) -> anyhow::Result<()> {
    let text = crate::io::text::read_text(&args.dump)
        .with_context(|| format!("cannot read {}", args.dump.display()))?;
    let pile = parse_dump(&text, &args.dump)?;
    let min_radius = pile
        .iter()
        .map(|s| s.radius_mm)
        .fold(f64::INFINITY, f64::min);
    let photos = photograph(&pile, min_radius)
        .with_context(|| format!("cannot measure the pile of {}", args.dump.display()))?;
    let (m, refused, mm_per_px) = (&photos.measurement, &photos.refused, photos.mm_per_px);
    if json {
        let report = Report {
            dump: args.dump.display().to_string(),
            spheres: pile.len(),
            mm_per_px,
            refused_views: refused,
            measurement: m,
        };
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
        return Ok(());
    }
    writeln!(
        out,
        "repose angle of {} ({} spheres): {:.2}° over {} views",
        args.dump.display(),
        pile.len(),
        m.angle_deg,
        m.views.len()
    )?;
    for v in &m.views {
        writeln!(
            out,
            "  azimuth {:5.1}°  {:6.2}°",
            v.azimuth_deg, v.angle.angle_deg
        )?;
    }
    for (azimuth, reason) in refused {
        writeln!(out, "  azimuth {azimuth:5.1}°  left out: {reason}")?;
    }
    Ok(())
}

/// The spheres of a text dump (module notes), in mm.
fn parse_dump(text: &str, path: &Path) -> anyhow::Result<Vec<Sphere>> {
    let mut lines = text.lines().enumerate();
    let header = lines
        .by_ref()
        .find_map(|(_, l)| l.strip_prefix("ITEM: ATOMS"))
        .with_context(|| format!("{}: no 'ITEM: ATOMS' line: not a dump", path.display()))?;
    let columns: Vec<&str> = header.split_whitespace().collect();
    let column = |name: &str| {
        columns.iter().position(|c| *c == name).with_context(|| {
            format!(
                "{}: the dump has no column '{name}' (it has: {})",
                path.display(),
                columns.join(" ")
            )
        })
    };
    let [r, x, y, z] = [column("radius")?, column("x")?, column("y")?, column("z")?];
    let mut pile = Vec::new();
    for (i, line) in lines {
        if line.starts_with("ITEM:") {
            bail!(
                "{}:{}: a second section: give a dump of one time step",
                path.display(),
                i + 1
            );
        }
        if line.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let value = |k: usize, name: &str| -> anyhow::Result<f64> {
            let v: f64 = fields
                .get(k)
                .with_context(|| format!("{}:{}: no {name} value", path.display(), i + 1))?
                .parse()
                .with_context(|| format!("{}:{}: {name} is not a number", path.display(), i + 1))?;
            if !v.is_finite() {
                bail!("{}:{}: {name} is not finite", path.display(), i + 1);
            }
            Ok(v * LENGTH_M_TO_MM)
        };
        let radius_mm = value(r, "radius")?;
        if radius_mm <= 0.0 {
            bail!("{}:{}: the radius must be positive", path.display(), i + 1);
        }
        pile.push(Sphere {
            centre_mm: [value(x, "x")?, value(y, "y")?, value(z, "z")?],
            radius_mm,
        });
    }
    if pile.is_empty() {
        bail!("{}: the dump holds no spheres", path.display());
    }
    Ok(pile)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dump_columns_by_name_in_metres() {
        let text = "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n\
                    -1 1\n-1 1\n0 1\nITEM: ATOMS id x y z radius\n1 0.001 0.002 0.003 0.004\n\
                    2 -0.01 0 0.02 0.005\n";
        let pile = parse_dump(text, Path::new("d")).unwrap();
        assert_eq!(pile.len(), 2);
        assert_eq!(pile[0].centre_mm, [1.0, 2.0, 3.0]);
        assert_eq!(pile[0].radius_mm, 4.0);
        assert_eq!(pile[1].centre_mm, [-10.0, 0.0, 20.0]);
    }

    #[test]
    fn bad_dumps_are_refused_with_the_line() {
        let no_radius = "ITEM: ATOMS id x y z\n1 0 0 0\n";
        let err = parse_dump(no_radius, Path::new("d"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("no column 'radius'"), "{err}");
        let bad = "ITEM: ATOMS id radius x y z\n1 0.004 0 0 0\n2 0.004 nan 0 0\n";
        let err = parse_dump(bad, Path::new("d")).unwrap_err().to_string();
        assert!(err.contains("d:3: x is not"), "{err}");
        let err = parse_dump("hello\n", Path::new("d"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("not a dump"), "{err}");
        let empty = "ITEM: ATOMS id radius x y z\n";
        assert!(parse_dump(empty, Path::new("d")).is_err());
    }
}
