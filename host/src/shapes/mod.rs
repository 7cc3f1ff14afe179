//! Pod shapes and their sphere fillings (issue 4 item 1).
//!
//! - [`PodShape`]: the three harvest-time shapes of seed 000 §2.2 (normal, cocoon,
//!   single-grain) as implicit solids of length × width × thickness, mm; [`ShapeMix`]: their
//!   fractions in a sample.
//! - [`read_stl`]: a scanned pod from a binary or ASCII STL file, as a closed
//!   [`TriangleMesh`]; [`pod_triangles`] and [`binary_stl_bytes`] export an analytic pod.
//! - [`fill_with_spheres`]: a deterministic filling of any [`Solid`] with overlapping
//!   spheres, at a sphere count or a covered fraction ("smoothness").
//! - [`filling_report()`]: the filling's volume, mass (density 582.36 kg/m³, seed 000 §3.1.1),
//!   centre of mass and principal inertia against the solid's;
//!   [`SphereFilling::in_principal_frame`] moves a filling to its principal frame.
//! - [`filling_csv()`] and [`write_fillings_svg`]: the filling as CSV rows and a picture.
//!
//! All lengths are mm in the body frame: origin at the pod's geometric centre, x along the
//! width, y along the thickness, z along the length (seed 001 §2.1).
//!
//! ```
//! use arachis::shapes::*;
//! let pod = PodShape::seed001_mean(PodKind::Normal);
//! let options = FillOptions { resolution: 32, target: FillTarget::SphereCount(7) };
//! let filling = fill_with_spheres(&pod, &options).unwrap();
//! let report = filling_report(&pod, &filling, 64, POD_DENSITY_KG_M3).unwrap();
//! assert_eq!(report.sphere_count, 7);
//! assert!(report.volume_rel_error < 0.0); // inscribed spheres fall short of the pod
//! ```

pub mod ball_cover;
pub mod distance_transform;
pub mod error;
pub mod filling_csv;
pub mod filling_report;
pub mod mass_properties;
pub mod picture;
pub mod pod_mesh;
pub mod pod_shape;
pub mod shape_mix;
pub mod solid;
pub mod sphere_fill;
pub mod stl;
pub mod triangle_mesh;
pub mod voxel_grid;

pub use error::ShapeError;
pub use filling_csv::{filling_csv, read_filling_csv, write_filling_csv};
pub use filling_report::{
    filling_report, voxelize_spheres, FillingReport, DEFAULT_REPORT_RESOLUTION,
};
pub use mass_properties::{
    ellipsoid_mass_properties, voxel_mass_properties, MassProperties, IDENTITY_AXES,
    POD_DENSITY_KG_M3,
};
pub use picture::{fillings_svg, write_fillings_svg, PicturePanel};
pub use pod_mesh::pod_triangles;
pub use pod_shape::{PodKind, PodShape};
pub use shape_mix::{apportion, ShapeMix};
pub use solid::Solid;
pub use sphere_fill::{
    fill_with_spheres, FillOptions, FillTarget, Sphere, SphereFilling, DEFAULT_FILL_RESOLUTION,
};
pub use stl::{ascii_stl_text, binary_stl_bytes, parse_stl, read_stl, write_binary_stl};
pub use triangle_mesh::TriangleMesh;
pub use voxel_grid::{Aabb, VoxelGrid};
