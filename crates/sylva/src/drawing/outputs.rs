//! Every file a line-drawable tree can be written to, chosen by extension: vector files and
//! drawings streamed from the model, meshes built from its skeleton at most once. All outputs
//! are checked before the first is written, so a bad name leaves nothing half done.

use super::{DrawOptions, LineSource, draw_png, write_svg, write_vec};
use crate::ExportError;
use crate::export::{Materials, to_glb, write_atomically, write_atomically_with, write_obj};
use crate::mesh::{MeshOptions, TreeMesh, mesh_tree};
use crate::skeleton::Skeleton;
use std::path::{Path, PathBuf};

/// What a file holds, by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineFormat {
    /// Nagel's move/draw vector file (`.vec`).
    Vec,
    /// A projected drawing as SVG.
    Svg,
    /// A projected drawing as PNG.
    Png,
    /// A mesh as GLB.
    Glb,
    /// A mesh as OBJ + MTL.
    Obj,
    /// Plan symbol and elevations for landscape CAD, as DXF (from the skeleton).
    Dxf,
}

impl LineFormat {
    /// The format of `path`, or an error naming what is allowed.
    pub fn of(path: &Path) -> Result<Self, ExportError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        Ok(match ext.as_deref() {
            Some("vec") => Self::Vec,
            Some("svg") => Self::Svg,
            Some("png") => Self::Png,
            Some("glb") => Self::Glb,
            Some("obj") => Self::Obj,
            Some("dxf") => Self::Dxf,
            _ => {
                return Err(ExportError::Output(format!(
                    "output {}: unknown format; use .vec (vector file), .svg or .png (drawing), \
                     .glb or .obj (mesh), .dxf (plan and elevations for CAD)",
                    path.display()
                )));
            }
        })
    }

    /// Whether the format holds a mesh (and so needs stem radii).
    pub fn is_mesh(self) -> bool {
        matches!(self, Self::Glb | Self::Obj)
    }
}

/// An output checked by [`plan`]: where, and in which format.
pub type Planned = (PathBuf, LineFormat);

/// Checks every output before anything is written: known formats, no folders, no repeats.
pub fn plan(outputs: &[PathBuf]) -> Result<Vec<Planned>, ExportError> {
    let mut planned: Vec<Planned> = Vec::new();
    for path in outputs {
        let format = LineFormat::of(path)?;
        if path.is_dir() {
            return Err(ExportError::Output(format!(
                "output {}: is a folder; give a file name",
                path.display()
            )));
        }
        if planned.iter().any(|(p, _)| p == path) {
            return Err(ExportError::Output(format!(
                "output {} is named twice",
                path.display()
            )));
        }
        planned.push((path.clone(), format));
    }
    Ok(planned)
}

/// Whether any planned output is a mesh.
pub fn wants_mesh(planned: &[Planned]) -> bool {
    planned.iter().any(|(_, f)| f.is_mesh())
}

/// How meshes are made and coloured.
#[derive(Default)]
pub struct MeshLook {
    /// Ring resolution.
    pub options: MeshOptions,
    /// Bark and leaf colours.
    pub materials: Materials,
}

/// Where a mesh output's skeleton comes from.
pub enum Meshable<'a> {
    /// At hand: the same skeleton the lines are drawn from.
    Skeleton(&'a Skeleton),
    /// Built only if a mesh is asked for (the fractal streams its lines without one).
    Build(&'a dyn Fn() -> Skeleton),
    /// Already meshed by the caller (who drew a picture of it too): the skeleton and its mesh.
    Mesh(&'a Skeleton, &'a TreeMesh),
    /// Nothing to mesh (a vector file has no radii); callers refuse mesh outputs first.
    Nothing,
}

/// Writes every planned output: lines straight from `source` as `options` draw them, a mesh
/// (made at most once, and only if asked for) from `mesh`. Returns a line per file saying
/// what it holds.
pub fn write_outputs(
    planned: &[Planned],
    options: &DrawOptions,
    source: &dyn LineSource,
    mesh: Meshable,
    name: &str,
    look: &MeshLook,
) -> Result<Vec<String>, ExportError> {
    let mut meshed: Option<TreeMesh> = None;
    let mut written = Vec::new();
    for (path, format) in planned {
        let what = match format {
            LineFormat::Vec => {
                write_atomically_with(path, |w| write_vec(source, w).map(drop))?;
                "vector file".to_string()
            }
            LineFormat::Svg => {
                write_atomically_with(path, |w| write_svg(source, options, w).map(drop))?;
                format!("{} view, SVG", options.view.name())
            }
            LineFormat::Png => {
                write_atomically(path, &draw_png(source, options))?;
                format!("{} view, PNG", options.view.name())
            }
            LineFormat::Dxf => {
                let built;
                let skeleton = match &mesh {
                    Meshable::Skeleton(s) | Meshable::Mesh(s, _) => *s,
                    Meshable::Build(build) => {
                        built = build();
                        &built
                    }
                    Meshable::Nothing => {
                        return Err(ExportError::Output(format!(
                            "{name}: lines only; a DXF plan and elevations are drawn from a \
                             tree's stems and leaves"
                        )));
                    }
                };
                let drawing = super::cad::tree_dxf(skeleton, name)?;
                write_atomically(path, &super::cad::to_bytes(&drawing)?)?;
                format!(
                    "DXF: plan and elevations, {} stems, {} leaves",
                    skeleton.stems.len(),
                    skeleton.leaves.len()
                )
            }
            LineFormat::Glb | LineFormat::Obj => {
                let mesh = match (&mut meshed, &mesh) {
                    (_, Meshable::Mesh(_, m)) => *m,
                    (Some(m), _) => &*m,
                    (slot, Meshable::Skeleton(s)) => slot.insert(mesh_tree(s, &look.options)),
                    (slot, Meshable::Build(build)) => {
                        slot.insert(mesh_tree(&build(), &look.options))
                    }
                    (None, Meshable::Nothing) => {
                        return Err(ExportError::Output(format!(
                            "{name}: lines only, nothing to mesh"
                        )));
                    }
                };
                if *format == LineFormat::Glb {
                    write_atomically(path, &to_glb(mesh, name, &look.materials)?)?;
                } else {
                    write_obj(path, mesh, name, &look.materials)?;
                }
                format!("mesh, {} triangles", mesh.triangle_count())
            }
        };
        written.push(format!("{} ({what})", path.display()));
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_checked_before_any_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.svg");
        let e = plan(&[a.clone(), a.clone()]).unwrap_err().to_string();
        assert!(e.contains("named twice"), "{e}");
        let e = plan(&[dir.path().join("a.dwg")]).unwrap_err().to_string();
        assert!(e.contains("unknown format") && e.contains(".vec"), "{e}");
        let folder = dir.path().join("b.png");
        std::fs::create_dir(&folder).unwrap();
        assert!(plan(&[folder]).is_err());
        let planned = plan(&[a.clone(), dir.path().join("a.vec")]).unwrap();
        assert!(!wants_mesh(&planned));
        let lines = vec![vec![glam::Vec3::ZERO, glam::Vec3::Z]];
        let options = DrawOptions::default();
        let written = write_outputs(
            &planned,
            &options,
            &lines,
            Meshable::Nothing,
            "line",
            &MeshLook::default(),
        )
        .unwrap();
        assert_eq!(written.len(), 2);
        assert!(std::fs::read_to_string(&a).unwrap().contains("<svg"));
        let glb = plan(&[dir.path().join("c.glb")]).unwrap();
        let e = write_outputs(
            &glb,
            &options,
            &lines,
            Meshable::Nothing,
            "l",
            &Default::default(),
        );
        assert!(e.unwrap_err().to_string().contains("nothing to mesh"));
    }
}
