//! Writing trees that can be drawn as lines (`fractal`, `whisk`, `stick`, `draw`): vector files
//! and drawings streamed from the model, meshes built from its skeleton.

use crate::args::{DrawArgs, LineOutputArgs, LineView};
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use sylva::Skeleton;
use sylva::drawing::{DrawOptions, LineSource, View, draw_png, write_svg, write_vec};
use sylva::export::{Materials, to_glb, write_atomically, write_atomically_with, write_obj};
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineFormat {
    Vec,
    Svg,
    Png,
    Glb,
    Obj,
}

impl LineFormat {
    fn of(path: &Path) -> Result<Self> {
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
            _ => bail!(
                "output {}: unknown format; use .vec (vector file), .svg or .png (drawing), \
                 .glb or .obj (mesh)",
                path.display()
            ),
        })
    }

    fn is_mesh(self) -> bool {
        matches!(self, Self::Glb | Self::Obj)
    }
}

/// Checks every output before anything is written: known formats, no folders, no repeats.
pub fn plan(out: &LineOutputArgs) -> Result<Vec<(PathBuf, LineFormat)>> {
    let mut planned: Vec<(PathBuf, LineFormat)> = Vec::new();
    for path in &out.outputs {
        let format = LineFormat::of(path)?;
        if path.is_dir() {
            bail!("output {}: is a folder; give a file name", path.display());
        }
        if planned.iter().any(|(p, _)| p == path) {
            bail!("output {} is named twice", path.display());
        }
        planned.push((path.clone(), format));
    }
    Ok(planned)
}

/// The drawing settings the flags ask for.
pub fn draw_options(out: &LineOutputArgs) -> DrawOptions {
    DrawOptions {
        view: match out.view {
            LineView::Front => View::Front,
            LineView::Side => View::Side,
            LineView::Top => View::Top,
            LineView::Perspective => View::Perspective,
            LineView::Overlay => View::Overlay,
        },
        width: out.size.0,
        height: out.size.1,
        ..Default::default()
    }
}

/// How meshes are made and coloured.
#[derive(Default)]
pub struct MeshLook {
    pub options: MeshOptions,
    pub materials: Materials,
}

/// Where a mesh output's skeleton comes from.
pub enum Meshable<'a> {
    /// At hand: the same skeleton the lines are drawn from.
    Skeleton(&'a Skeleton),
    /// Built only if a mesh is asked for (the fractal streams its lines without one).
    Build(&'a dyn Fn() -> Skeleton),
    /// Nothing to mesh (a vector file has no radii); callers refuse mesh outputs first.
    Nothing,
}

/// Writes every planned output: lines straight from `source`, a mesh (made at most once, and
/// only if asked for) from `mesh`. Returns a line per file for the summary.
pub fn write(
    planned: &[(PathBuf, LineFormat)],
    out: &LineOutputArgs,
    source: &dyn LineSource,
    mesh: Meshable,
    name: &str,
    look: &MeshLook,
) -> Result<Vec<String>> {
    let options = draw_options(out);
    let mut meshed: Option<TreeMesh> = None;
    let mut written = Vec::new();
    for (path, format) in planned {
        let what = match format {
            LineFormat::Vec => {
                write_atomically_with(path, |w| write_vec(source, w).map(drop))?;
                "vector file".to_string()
            }
            LineFormat::Svg => {
                write_atomically_with(path, |w| write_svg(source, &options, w).map(drop))?;
                format!("{} view, SVG", options.view.name())
            }
            LineFormat::Png => {
                write_atomically(path, &draw_png(source, &options))?;
                format!("{} view, PNG", options.view.name())
            }
            LineFormat::Glb | LineFormat::Obj => {
                if meshed.is_none() {
                    meshed = Some(match &mesh {
                        Meshable::Skeleton(s) => mesh_tree(s, &look.options),
                        Meshable::Build(build) => mesh_tree(&build(), &look.options),
                        Meshable::Nothing => bail!("{name}: lines only, nothing to mesh"),
                    });
                }
                let mesh = meshed.as_ref().expect("made above");
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

/// [`write`] for a model held as a skeleton.
pub fn write_skeleton(
    planned: &[(PathBuf, LineFormat)],
    out: &LineOutputArgs,
    skeleton: &Skeleton,
    name: &str,
    look: &MeshLook,
) -> Result<Vec<String>> {
    write(
        planned,
        out,
        skeleton,
        Meshable::Skeleton(skeleton),
        name,
        look,
    )
}

/// Whether any planned output is a mesh.
pub fn wants_mesh(planned: &[(PathBuf, LineFormat)]) -> bool {
    planned.iter().any(|(_, f)| f.is_mesh())
}

/// `sylva draw`: line drawings of a Weber–Penn species or a vector file.
pub fn draw(args: &DrawArgs) -> Result<()> {
    let planned = plan(&args.out)?;
    let is_vec = Path::new(&args.input)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vec"));
    if is_vec && args.age.is_some() {
        bail!(
            "{}: --age grows a street tree; a vector file is drawn as it is",
            args.input
        );
    }
    let written = if is_vec {
        if wants_mesh(&planned) {
            bail!(
                "{}: a vector file has lines but no stem radii; write .vec, .svg or .png",
                args.input
            );
        }
        let text = std::fs::read_to_string(&args.input)
            .with_context(|| format!("cannot read {}", args.input))?;
        let lines = sylva::drawing::read_vec(&text, &args.input)?;
        if lines.iter().all(|l| l.len() < 2) {
            bail!("{}: no lines to draw (no `L` after a `P`)", args.input);
        }
        write(
            &planned,
            &args.out,
            &lines,
            Meshable::Nothing,
            &args.input,
            &MeshLook::default(),
        )?
    } else if let Some(age) = args.age {
        let db = sylva::growth::Database::builtin();
        let measured = db.find(&args.region, &args.input)?;
        if !(0.0..=crate::grow::MAX_AGE).contains(&age) {
            bail!(
                "--age {age}: expected 0..{} years (the data for {} cover {:.0} to {:.0})",
                crate::grow::MAX_AGE,
                measured.label(),
                measured.ages.0,
                measured.ages.1
            );
        }
        let (bark, leaves) = crate::shared::street_tree_colours(&measured);
        let name = format!("{} at {age} years", measured.species.common);
        let mut grower = sylva::growth::Grower::new(
            measured,
            sylva::growth::GrowthOptions {
                seed: args.tree.seed,
                ..Default::default()
            },
        );
        grower.advance_to(age);
        let mut skeleton = grower.skeleton();
        if args.tree.no_leaves {
            skeleton.leaves.clear();
        }
        let look = MeshLook {
            options: MeshOptions {
                quality: 0.6,
                ..Default::default()
            },
            materials: Materials::from_srgb(bark, leaves),
        };
        write_skeleton(&planned, &args.out, &skeleton, &name, &look)?
    } else {
        let params = crate::shared::load_params(&args.input, &args.tree.set)?;
        let skeleton = sylva::generate(&params, &args.tree.options())?;
        let look = MeshLook {
            options: crate::shared::mesh_options(&params, args.tree.quality),
            materials: Materials::from_srgb(params.bark_color, params.leaf_color),
        };
        write_skeleton(&planned, &args.out, &skeleton, &params.name, &look)?
    };
    for line in written {
        println!("wrote {line}");
    }
    Ok(())
}
