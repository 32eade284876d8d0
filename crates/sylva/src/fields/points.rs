//! Point clouds: reading PLY and XYZ files, and fitting a trunk and leaf lobes to them as
//! Fields' report describes (section 6.1): the trunk from horizontal slices, up to where a slice
//! grows much wider than those below it, and lobes from clusters of the canopy's points.

use super::lobe::Lobe;
use super::pipeline::{Placement, TrunkPiece};
use crate::error::ParamsError;
use crate::rng::{Random, StreamKey};
use glam::Vec3;

/// Most points read from a file.
pub const MAX_POINTS: usize = 5_000_000;

/// Which axis of the file points up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Up {
    /// Z up (scanners, CAD): kept as is.
    Z,
    /// Y up (Kinect, game engines): (x, y, z) becomes (x, −z, y).
    Y,
}

/// Largest coordinate accepted, metres: beyond any georeferenced scan (UTM northings reach
/// 1e7), so a number garbled into 1e19 is refused rather than fitted as a crown that wide.
const MAX_COORDINATE: f32 = 1e7;

fn usable(v: f32) -> bool {
    v.is_finite() && v.abs() <= MAX_COORDINATE
}

fn syntax(name: &str, line: Option<usize>, message: String) -> ParamsError {
    ParamsError::Syntax {
        source_name: match line {
            Some(l) => format!("{name}, line {l}"),
            None => name.to_string(),
        },
        message,
    }
}

fn orient(p: [f32; 3], up: Up) -> Vec3 {
    match up {
        Up::Z => Vec3::from(p),
        Up::Y => Vec3::new(p[0], -p[2], p[1]),
    }
}

/// Reads a `.ply` (ASCII or binary, vertex x, y, z) or `.xyz` (one `x y z` per line) file.
pub fn read_points(name: &str, bytes: &[u8], up: Up) -> Result<Vec<Vec3>, ParamsError> {
    let points = if name.to_ascii_lowercase().ends_with(".ply") {
        read_ply(name, bytes, up)?
    } else {
        read_xyz(name, bytes, up)?
    };
    if points.len() < 10 {
        return Err(syntax(
            name,
            None,
            format!("{} points; a tree needs at least 10", points.len()),
        ));
    }
    Ok(points)
}

fn read_xyz(name: &str, bytes: &[u8], up: Up) -> Result<Vec<Vec3>, ParamsError> {
    let text = std::str::from_utf8(bytes).map_err(|_| {
        syntax(
            name,
            None,
            "not a text file (expected `x y z` lines)".into(),
        )
    })?;
    let mut points = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with("//") {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        if fields.len() < 3 {
            return Err(syntax(
                name,
                Some(i + 1),
                format!("expected `x y z`, found `{line}`"),
            ));
        }
        let mut p = [0.0f32; 3];
        for (slot, f) in p.iter_mut().zip(&fields) {
            *slot = f
                .parse::<f32>()
                .ok()
                .filter(|v| usable(*v))
                .ok_or_else(|| {
                    syntax(
                        name,
                        Some(i + 1),
                        format!("`{f}` is not a coordinate (a finite number of at most {MAX_COORDINATE:e} m)"),
                    )
                })?;
        }
        if points.len() >= MAX_POINTS {
            return Err(syntax(
                name,
                Some(i + 1),
                format!("more than {MAX_POINTS} points; thin the cloud first"),
            ));
        }
        points.push(orient(p, up));
    }
    Ok(points)
}

#[derive(Clone, Copy)]
enum Format {
    Ascii,
    Little,
    Big,
}

fn scalar_size(kind: &str) -> Option<usize> {
    Some(match kind {
        "char" | "uchar" | "int8" | "uint8" => 1,
        "short" | "ushort" | "int16" | "uint16" => 2,
        "int" | "uint" | "float" | "int32" | "uint32" | "float32" => 4,
        "double" | "float64" => 8,
        _ => return None,
    })
}

fn read_ply(name: &str, bytes: &[u8], up: Up) -> Result<Vec<Vec3>, ParamsError> {
    // The header is ASCII, up to and including `end_header\n`.
    let end = bytes
        .windows(10)
        .position(|w| w == b"end_header")
        .ok_or_else(|| syntax(name, Some(1), "no `end_header`: not a PLY file".into()))?;
    let header = std::str::from_utf8(&bytes[..end])
        .map_err(|_| syntax(name, None, "the PLY header is not text".into()))?;
    let mut body = end + 10;
    while body < bytes.len() && (bytes[body] == b'\r' || bytes[body] == b' ') {
        body += 1;
    }
    if body < bytes.len() && bytes[body] == b'\n' {
        body += 1;
    }
    let header_lines = header.lines().count();
    let mut format = None;
    let mut vertices: Option<usize> = None;
    let mut current_is_vertex = false;
    let mut before_vertex = 0usize; // bytes (binary) or lines (ASCII) of earlier elements
    let mut earlier_unknown = false;
    let mut props: Vec<(String, usize)> = Vec::new();
    for (i, line) in header.lines().enumerate() {
        let line_no = i + 1;
        let f: Vec<&str> = line.split_whitespace().collect();
        match f.as_slice() {
            ["ply"] if i == 0 => {}
            _ if i == 0 => return Err(syntax(name, Some(1), "expected `ply`".into())),
            ["format", kind, _] => {
                format = Some(match *kind {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Little,
                    "binary_big_endian" => Format::Big,
                    other => {
                        return Err(syntax(
                            name,
                            Some(line_no),
                            format!("unknown format `{other}`"),
                        ));
                    }
                })
            }
            ["element", kind, count] => {
                let count: usize = count.parse().map_err(|_| {
                    syntax(
                        name,
                        Some(line_no),
                        format!("element count `{count}` is not a number"),
                    )
                })?;
                current_is_vertex = *kind == "vertex";
                if current_is_vertex {
                    if count > MAX_POINTS {
                        return Err(syntax(
                            name,
                            Some(line_no),
                            format!(
                                "{count} vertices, more than {MAX_POINTS}; thin the cloud first"
                            ),
                        ));
                    }
                    vertices = Some(count);
                } else if vertices.is_none() {
                    // Elements before the vertices would have to be skipped; rare in clouds.
                    before_vertex += count;
                    earlier_unknown = true;
                }
            }
            ["property", "list", ..] if current_is_vertex => {
                return Err(syntax(
                    name,
                    Some(line_no),
                    "list properties on vertices are not supported".into(),
                ));
            }
            ["property", kind, prop] if current_is_vertex => {
                let size = scalar_size(kind).ok_or_else(|| {
                    syntax(
                        name,
                        Some(line_no),
                        format!("unknown property type `{kind}`"),
                    )
                })?;
                props.push((prop.to_string(), size));
            }
            _ => {}
        }
    }
    let format = format.ok_or_else(|| syntax(name, None, "no `format` line".into()))?;
    let count = vertices.ok_or_else(|| syntax(name, None, "no `element vertex`".into()))?;
    if earlier_unknown && before_vertex > 0 {
        return Err(syntax(
            name,
            None,
            "elements before `vertex` are not supported".into(),
        ));
    }
    let index = |axis: &str| props.iter().position(|(p, _)| p == axis);
    let (Some(ix), Some(iy), Some(iz)) = (index("x"), index("y"), index("z")) else {
        return Err(syntax(
            name,
            None,
            "vertices need `x`, `y` and `z` properties".into(),
        ));
    };
    let mut points = Vec::with_capacity(count);
    match format {
        Format::Ascii => {
            let text = std::str::from_utf8(&bytes[body..])
                .map_err(|_| syntax(name, None, "ASCII PLY body is not text".into()))?;
            let mut lines = text.lines().enumerate();
            for _ in 0..count {
                let (i, line) = loop {
                    match lines.next() {
                        Some((_, l)) if l.trim().is_empty() => continue,
                        Some(x) => break x,
                        None => {
                            return Err(syntax(
                                name,
                                None,
                                format!("the file ends after {} of {count} vertices", points.len()),
                            ));
                        }
                    }
                };
                let line_no = header_lines + 1 + i + 1;
                let f: Vec<&str> = line.split_whitespace().collect();
                if f.len() < props.len() {
                    return Err(syntax(
                        name,
                        Some(line_no),
                        format!("expected {} values, found {}", props.len(), f.len()),
                    ));
                }
                let mut p = [0.0f32; 3];
                for (slot, k) in p.iter_mut().zip([ix, iy, iz]) {
                    *slot = f[k]
                        .parse::<f32>()
                        .ok()
                        .filter(|v| usable(*v))
                        .ok_or_else(|| {
                            syntax(
                                name,
                                Some(line_no),
                                format!(
                                    "`{}` is not a coordinate (a finite number of at most {MAX_COORDINATE:e} m)",
                                    f[k]
                                ),
                            )
                        })?;
                }
                points.push(orient(p, up));
            }
        }
        Format::Little | Format::Big => {
            let stride: usize = props.iter().map(|(_, s)| s).sum();
            let offsets: Vec<usize> = props
                .iter()
                .scan(0, |acc, (_, s)| {
                    let o = *acc;
                    *acc += s;
                    Some(o)
                })
                .collect();
            let need = stride * count;
            if bytes.len() < body + need {
                return Err(syntax(
                    name,
                    None,
                    format!(
                        "the file ends early: {count} vertices of {stride} bytes need {need} bytes, {} are there",
                        bytes.len() - body
                    ),
                ));
            }
            let read = |at: usize, size: usize| -> f32 {
                let b = &bytes[at..at + size];
                let little = matches!(format, Format::Little);
                match size {
                    4 => {
                        let a = [b[0], b[1], b[2], b[3]];
                        if little {
                            f32::from_le_bytes(a)
                        } else {
                            f32::from_be_bytes(a)
                        }
                    }
                    8 => {
                        let a = [b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]];
                        (if little {
                            f64::from_le_bytes(a)
                        } else {
                            f64::from_be_bytes(a)
                        }) as f32
                    }
                    _ => f32::NAN,
                }
            };
            for v in 0..count {
                let base = body + v * stride;
                let mut p = [0.0f32; 3];
                for (slot, k) in p.iter_mut().zip([ix, iy, iz]) {
                    *slot = read(base + offsets[k], props[k].1);
                }
                if p.iter().any(|c| !usable(*c)) {
                    return Err(syntax(
                        name,
                        None,
                        format!(
                            "vertex {v}: coordinates must be float or double, finite and at most {MAX_COORDINATE:e} m"
                        ),
                    ));
                }
                points.push(orient(p, up));
            }
        }
    }
    Ok(points)
}

/// What fitting found.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// Trunk (one piece from the ground to the crown's base) and lobes, moved so that the trunk
    /// starts at the origin.
    pub placement: Placement,
    /// Height of the crown's base above the lowest point.
    pub crown_base: f32,
    /// The canopy points (above the crown base), in the placement's frame.
    pub canopy: Vec<Vec3>,
}

/// Share of a cluster's points a lobe must hold (its radius is this quantile of distances).
const COVER: f32 = 0.96;

/// Fits a trunk and `lobes` lobes (or 1 to 8, whichever describes the canopy most tightly) to
/// the points.
pub fn fit(points: &[Vec3], lobes: Option<usize>, seed: u64) -> Fit {
    let (lo, hi) = points.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| {
        (lo.min(*p), hi.max(*p))
    });
    let height = (hi.z - lo.z).max(1e-6);
    // Horizontal slices, 2% of the height each; a slice's width is twice the distance from its
    // centre within which 95% of its points lie.
    let n = 50usize;
    let mut slices: Vec<Vec<Vec3>> = vec![Vec::new(); n];
    for p in points {
        let k = (((p.z - lo.z) / height) * n as f32) as usize;
        slices[k.min(n - 1)].push(*p);
    }
    let stats: Vec<Option<(Vec3, f32)>> = slices
        .iter()
        .map(|s| {
            if s.len() < 3 {
                return None;
            }
            let c = s.iter().copied().sum::<Vec3>() / s.len() as f32;
            let mut d: Vec<f32> = s.iter().map(|p| (*p - c).truncate().length()).collect();
            d.sort_by(f32::total_cmp);
            Some((c, 2.0 * d[(d.len() - 1) * 95 / 100]))
        })
        .collect();
    // The crown starts at the first slice much wider (3x) than the mean of the slices below.
    let mut base_slice = 0;
    let (mut sum, mut count) = (0.0f32, 0);
    for (k, s) in stats.iter().enumerate() {
        let Some((_, w)) = s else { continue };
        if count >= 2 && *w > 3.0 * sum / count as f32 {
            base_slice = k;
            break;
        }
        sum += w;
        count += 1;
        base_slice = k + 1;
    }
    if base_slice >= n {
        base_slice = 0; // no narrow trunk at all: the crown reaches the ground
    }
    let crown_base = base_slice as f32 / n as f32 * height;
    // The trunk's axis: a straight line fitted through the slices' centres, leaving out the
    // slice just below the crown, which may already hold the crown's lowest points.
    let mut centres: Vec<Vec3> = stats[..base_slice]
        .iter()
        .flatten()
        .map(|(c, _)| *c)
        .collect();
    if centres.len() > 2 {
        centres.pop();
    }
    let axis_at = |z: f32| -> Vec3 {
        match centres.len() {
            0 => {
                let c = points.iter().copied().sum::<Vec3>() / points.len() as f32;
                Vec3::new(c.x, c.y, z)
            }
            1 => Vec3::new(centres[0].x, centres[0].y, z),
            n => {
                let mz = centres.iter().map(|c| c.z).sum::<f32>() / n as f32;
                let mxy = centres.iter().map(|c| c.truncate()).sum::<glam::Vec2>() / n as f32;
                let szz: f32 = centres.iter().map(|c| (c.z - mz).powi(2)).sum();
                let sxy: glam::Vec2 = centres
                    .iter()
                    .map(|c| (c.truncate() - mxy) * (c.z - mz))
                    .sum();
                let slope = if szz > 1e-12 {
                    sxy / szz
                } else {
                    glam::Vec2::ZERO
                };
                (mxy + slope * (z - mz)).extend(z)
            }
        }
    };
    let ground = axis_at(lo.z);
    let top = if base_slice > 0 {
        axis_at(lo.z + crown_base)
    } else {
        ground + Vec3::Z * (0.05 * height)
    };
    let canopy: Vec<Vec3> = points
        .iter()
        .filter(|p| p.z >= lo.z + crown_base)
        .map(|p| *p - ground)
        .collect();
    let mut random = StreamKey::from_seed(seed).child(9).stream();
    let fitted = match lobes {
        Some(k) => cluster(&canopy, k.max(1), &mut random).1,
        None => {
            // The fewest lobes whose total volume is least, with a 15% price per lobe so that a
            // round crown stays one lobe.
            let mut best: Option<(f32, Vec<Lobe>)> = None;
            for k in 1..=8.min(canopy.len().max(1)) {
                let (volume, lobes) = cluster(&canopy, k, &mut random);
                let score = volume * (1.0 + 0.15 * k as f32);
                if best.as_ref().is_none_or(|(s, _)| score < *s) {
                    best = Some((score, lobes));
                }
            }
            best.map(|b| b.1).unwrap_or_default()
        }
    };
    Fit {
        placement: Placement {
            trunks: vec![TrunkPiece {
                parent: None,
                start: Vec3::ZERO,
                end: top - ground,
            }],
            lobes: fitted,
        },
        crown_base,
        canopy,
    }
}

/// k-means (k-means++ start, 30 rounds) and a lobe per cluster: its centroid and the distance
/// holding `COVER` of its points. Returns the lobes' total volume and the lobes.
fn cluster(points: &[Vec3], k: usize, random: &mut Random) -> (f32, Vec<Lobe>) {
    if points.is_empty() {
        return (0.0, Vec::new());
    }
    let k = k.min(points.len());
    let mut centres = vec![points[(random.unit() * points.len() as f64) as usize % points.len()]];
    while centres.len() < k {
        let d: Vec<f32> = points
            .iter()
            .map(|p| {
                centres
                    .iter()
                    .map(|c| c.distance_squared(*p))
                    .fold(f32::MAX, f32::min)
            })
            .collect();
        let total: f32 = d.iter().sum();
        let mut pick = random.unit() as f32 * total;
        let mut chosen = points.len() - 1;
        for (i, w) in d.iter().enumerate() {
            if pick < *w {
                chosen = i;
                break;
            }
            pick -= w;
        }
        centres.push(points[chosen]);
    }
    let mut label = vec![0usize; points.len()];
    for _ in 0..30 {
        for (i, p) in points.iter().enumerate() {
            label[i] = (0..k)
                .min_by(|&a, &b| {
                    centres[a]
                        .distance_squared(*p)
                        .total_cmp(&centres[b].distance_squared(*p))
                })
                .unwrap();
        }
        let mut sums = vec![(Vec3::ZERO, 0usize); k];
        for (i, p) in points.iter().enumerate() {
            sums[label[i]].0 += *p;
            sums[label[i]].1 += 1;
        }
        let mut moved = false;
        for (c, (s, n)) in centres.iter_mut().zip(&sums) {
            if *n > 0 {
                let next = *s / *n as f32;
                moved |= next.distance_squared(*c) > 1e-12;
                *c = next;
            }
        }
        if !moved {
            break;
        }
    }
    let mut lobes = Vec::with_capacity(k);
    let mut volume = 0.0;
    for (j, c) in centres.iter().enumerate() {
        let mut d: Vec<f32> = points
            .iter()
            .zip(&label)
            .filter(|(_, l)| **l == j)
            .map(|(p, _)| p.distance(*c))
            .collect();
        if d.is_empty() {
            continue;
        }
        d.sort_by(f32::total_cmp);
        let r = d[((d.len() - 1) as f32 * COVER) as usize].max(1e-3);
        volume += r * r * r;
        lobes.push(Lobe {
            centre: *c,
            radius: r,
        });
    }
    (volume, lobes)
}

/// Share of `points` inside at least one lobe (spheres).
pub fn coverage(points: &[Vec3], lobes: &[Lobe]) -> f32 {
    if points.is_empty() {
        return 1.0;
    }
    let inside = points
        .iter()
        .filter(|p| lobes.iter().any(|l| l.centre.distance(**p) <= l.radius))
        .count();
    inside as f32 / points.len() as f32
}
