//! A closed triangle mesh (from an STL file) as a [`Solid`]: inside test by ray parity.
//!
//! Vertices are welded when their coordinates are bit-identical (STL exporters write a
//! shared vertex with the same digits each time); the mesh is closed when every edge is
//! shared by exactly two triangles. Triangles whose welded vertices repeat have no area and
//! are dropped.
//!
//! Inside test: a ray from the point along +z crosses the surface an odd number of times.
//! A ray through an edge or a vertex must count exactly one of the triangles meeting
//! there, so the point-in-triangle test (in the xy projection) uses edge functions computed
//! with the edge's endpoints in a fixed order (so two triangles sharing an edge get exactly
//! opposite values) and a tie rule that acts as a fixed infinitesimal shift of the ray
//! (the rasterisers' "top-left" rule).

use std::collections::HashMap;
use std::path::Path;

use super::error::ShapeError;
use super::solid::Solid;
use super::voxel_grid::{Aabb, VoxelGrid};

/// Relative widening (of a voxel edge) of a triangle's xy box when finding its columns.
const COLUMN_SLACK: f64 = 1e-6;

/// A closed triangle mesh, mm.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleMesh {
    /// Welded vertices, mm.
    pub vertices_mm: Vec<[f64; 3]>,
    /// Triangles as indices into `vertices_mm`.
    pub triangles: Vec<[usize; 3]>,
}

fn vertex_key(v: &[f64; 3]) -> [u64; 3] {
    // +0.0 and −0.0 are the same point.
    v.map(|x| if x == 0.0 { 0 } else { x.to_bits() })
}

impl TriangleMesh {
    /// Welds `triangles` (vertex coordinates, mm) into a mesh and checks it is closed;
    /// `path` names the source in errors.
    pub fn from_triangles(path: &Path, triangles: &[[[f64; 3]; 3]]) -> Result<Self, ShapeError> {
        let mut index_of: HashMap<[u64; 3], usize> = HashMap::new();
        let mut vertices_mm = Vec::new();
        let mut tris = Vec::with_capacity(triangles.len());
        for tri in triangles {
            let ids = tri.map(|v| {
                *index_of.entry(vertex_key(&v)).or_insert_with(|| {
                    vertices_mm.push(v);
                    vertices_mm.len() - 1
                })
            });
            if ids[0] != ids[1] && ids[1] != ids[2] && ids[0] != ids[2] {
                tris.push(ids);
            }
        }
        let not_closed = |reason: String| ShapeError::NotClosed {
            path: path.to_path_buf(),
            reason,
        };
        if tris.is_empty() {
            return Err(not_closed(
                "the mesh has no triangle with three distinct vertices".into(),
            ));
        }
        let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
        for t in &tris {
            for e in 0..3 {
                let (a, b) = (t[e], t[(e + 1) % 3]);
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        let mut bad: Vec<((usize, usize), usize)> =
            edges.into_iter().filter(|&(_, n)| n != 2).collect();
        if !bad.is_empty() {
            bad.sort();
            let ((a, b), n) = bad[0];
            return Err(not_closed(format!(
                "{} edges are not shared by exactly two triangles; e.g. the edge from {:?} to \
                 {:?} mm belongs to {n} triangle(s)",
                bad.len(),
                vertices_mm[a],
                vertices_mm[b]
            )));
        }
        Ok(TriangleMesh {
            vertices_mm,
            triangles: tris,
        })
    }

    /// Enclosed volume by the divergence theorem, |Σ v0·(v1 × v2)| / 6, mm³. Correct when
    /// the triangles are consistently oriented; an independent check of the voxel volume.
    pub fn enclosed_volume_mm3(&self) -> f64 {
        let sum: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices_mm[i]);
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum();
        sum.abs() / 6.0
    }

    /// The mesh scaled by `factor` (e.g. 1000 for a file in metres).
    pub fn scaled(&self, factor: f64) -> TriangleMesh {
        TriangleMesh {
            vertices_mm: self
                .vertices_mm
                .iter()
                .map(|v| v.map(|x| x * factor))
                .collect(),
            triangles: self.triangles.clone(),
        }
    }

    /// Height z, mm, where the vertical line through (x, y) crosses triangle `tri`, if it does.
    fn crossing(&self, tri: &[usize; 3], x: f64, y: f64) -> Option<f64> {
        let [p0, p1, p2] = tri.map(|i| self.vertices_mm[i]);
        let w0 = edge_function(p1, p2, x, y);
        let w1 = edge_function(p2, p0, x, y);
        let w2 = edge_function(p0, p1, x, y);
        let area = w0 + w1 + w2;
        if area == 0.0 {
            return None; // seen edge-on: a vertical triangle is never crossed
        }
        // Orient so the interior is on the positive side of every edge function.
        let sign = area.signum();
        let owned = |w: f64, a: [f64; 3], b: [f64; 3]| {
            let w = w * sign;
            let (dx, dy) = ((b[0] - a[0]) * sign, (b[1] - a[1]) * sign);
            w > 0.0 || (w == 0.0 && (dy > 0.0 || (dy == 0.0 && dx < 0.0)))
        };
        if owned(w0, p1, p2) && owned(w1, p2, p0) && owned(w2, p0, p1) {
            Some((w0 * p0[2] + w1 * p1[2] + w2 * p2[2]) / area)
        } else {
            None
        }
    }
}

/// Twice the signed area of (a, b, p) in the xy projection, computed with a and b in
/// lexicographic order so that the edge (b, a) gives exactly the negated value.
fn edge_function(a: [f64; 3], b: [f64; 3], x: f64, y: f64) -> f64 {
    let raw = |a: [f64; 3], b: [f64; 3]| (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
    if (a[0], a[1]) <= (b[0], b[1]) {
        raw(a, b)
    } else {
        -raw(b, a)
    }
}

impl Solid for TriangleMesh {
    fn bounds_mm(&self) -> Aabb {
        let start = Aabb {
            min_mm: [f64::INFINITY; 3],
            max_mm: [f64::NEG_INFINITY; 3],
        };
        self.vertices_mm.iter().fold(start, |b, v| {
            b.union(&Aabb {
                min_mm: *v,
                max_mm: *v,
            })
        })
    }

    fn contains_mm(&self, p: [f64; 3]) -> bool {
        let above = self
            .triangles
            .iter()
            .filter_map(|t| self.crossing(t, p[0], p[1]))
            .filter(|&z| z > p[2])
            .count();
        above % 2 == 1
    }

    /// Column by column: each triangle adds its crossing height to the columns whose
    /// (x, y) it covers; a voxel is inside when an odd number of crossings lie above it.
    fn voxelize(&self, grid: &VoxelGrid) -> Vec<bool> {
        let [nx, ny, nz] = grid.dims;
        let mut columns: Vec<Vec<f64>> = vec![Vec::new(); nx * ny];
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.vertices_mm[i]);
            // Widened a hair so rounding in the index range never drops a column that
            // passes exactly through a vertex or edge: the crossing test decides those.
            let slack = COLUMN_SLACK * grid.spacing_mm;
            let lo = |axis: usize| a[axis].min(b[axis]).min(c[axis]) - slack;
            let hi = |axis: usize| a[axis].max(b[axis]).max(c[axis]) + slack;
            for j in grid.index_range(1, lo(1), hi(1)) {
                for i in grid.index_range(0, lo(0), hi(0)) {
                    if let Some(z) = self.crossing(t, grid.coord_mm(0, i), grid.coord_mm(1, j)) {
                        columns[i + nx * j].push(z);
                    }
                }
            }
        }
        let mut inside = vec![false; grid.len()];
        for j in 0..ny {
            for i in 0..nx {
                let col = &columns[i + nx * j];
                for k in 0..nz {
                    let z = grid.coord_mm(2, k);
                    let above = col.iter().filter(|&&c| c > z).count();
                    inside[grid.index(i, j, k)] = above % 2 == 1;
                }
            }
        }
        inside
    }
}
