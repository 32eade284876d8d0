// Sylva's tree shader: sun + sky lighting, shadow map with PCF, two-sided translucent leaves,
// and a ground with a metre grid. World space is the model's: metres, Z up.

struct Globals {
    view_proj: mat4x4<f32>,
    light_view_proj: mat4x4<f32>,
    // xyz: unit vector towards the sun
    sun_dir: vec4<f32>,
    sun_color: vec4<f32>,
    sky_color: vec4<f32>,
    ground_bounce: vec4<f32>,
    // x: shadow map texel size, y: depth bias
    shadow: vec4<f32>,
    // xyz: the eye; w: pixels per metre at 1 m from it
    eye: vec4<f32>,
};

struct Material {
    color: vec4<f32>,
    // x: 0 opaque (bark, person), 1 leaf (two-sided, translucent), 2 ground (grid)
    kind: vec4<f32>,
};

@group(0) @binding(0) var<uniform> g: Globals;
@group(0) @binding(1) var shadow_map: texture_depth_2d;
@group(0) @binding(2) var shadow_sampler: sampler_comparison;
@group(1) @binding(0) var<uniform> m: Material;

struct VsIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    // A leaf's luminance class as a factor (1 for everything else).
    @location(2) shade: f32,
};

// Where a copy of a tree stands: xyz offset and scale, then cos and sin of its turn about Z.
struct Instance {
    @location(4) place: vec4<f32>,
    @location(5) turn: vec2<f32>,
    // x: how many stems or leaves each line or point stands for
    @location(6) stands_for: vec2<f32>,
};

fn turned(i: Instance, v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(i.turn.x * v.x - i.turn.y * v.y, i.turn.y * v.x + i.turn.x * v.y, v.z);
}

fn placed(i: Instance, p: vec3<f32>) -> vec3<f32> {
    return i.place.xyz + i.place.w * turned(i, p);
}

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) light_clip: vec4<f32>,
    @location(3) shade: f32,
};

fn surface_vertex(position: vec3<f32>, normal: vec3<f32>, shade: f32, i: Instance) -> VsOut {
    var out: VsOut;
    let world = placed(i, position);
    out.clip = g.view_proj * vec4<f32>(world, 1.0);
    out.world = world;
    out.normal = turned(i, normal);
    out.light_clip = g.light_view_proj * vec4<f32>(world, 1.0);
    out.shade = shade;
    return out;
}

@vertex
fn vs_main(v: VsIn, i: Instance) -> VsOut {
    return surface_vertex(v.position, v.normal, v.shade, i);
}

@vertex
fn vs_shadow(v: VsIn, i: Instance) -> @builtin(position) vec4<f32> {
    return g.light_view_proj * vec4<f32>(placed(i, v.position), 1.0);
}

// Anti-aliased grid lines every metre, stronger every 5 m.
fn grid(world: vec2<f32>) -> f32 {
    let w1 = fwidth(world);
    let d1 = abs(fract(world + 0.5) - 0.5) / max(w1, vec2<f32>(1e-4));
    let line1 = 1.0 - min(min(d1.x, d1.y), 1.0);
    let w5 = world / 5.0;
    let d5 = abs(fract(w5 + 0.5) - 0.5) / max(fwidth(w5), vec2<f32>(1e-4));
    let line5 = 1.0 - min(min(d5.x, d5.y) / 1.6, 1.0);
    return max(line1 * 0.35, line5 * 0.6);
}

// Bark, the ground and the person.
@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return main_colour(in);
}

fn main_colour(in: VsOut) -> vec4<f32> {
    let n = normalize(in.normal);
    var base = m.color.rgb * in.shade;
    if (m.kind.x > 1.5) {
        // Fade the grid out with distance so it never shimmers into noise.
        base = mix(base, base * 0.55, grid(in.world.xy));
    }
    let sun = g.sun_color.rgb * sunlit(in.light_clip);
    // Sky from above, light bounced off the ground from below.
    let hemi = mix(g.ground_bounce.rgb, g.sky_color.rgb, 0.5 + 0.5 * n.z);
    return vec4<f32>(base * (hemi + sun * max(dot(n, g.sun_dir.xyz), 0.0)), 1.0);
}

// Leaves: two-sided, and lit through when the sun is behind them. A pipeline of their own,
// rather than a branch in `fs_main`: llvmpipe runs both sides of a branch it cannot prove
// uniform.
@fragment
fn fs_leaf(in: VsOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return leaf_colour(in, front);
}

fn leaf_colour(in: VsOut, front: bool) -> vec4<f32> {
    var n = normalize(in.normal);
    if (!front) {
        n = -n;
    }
    let base = m.color.rgb * in.shade;
    let ndl = dot(n, g.sun_dir.xyz);
    let sun = g.sun_color.rgb * sunlit_leaf(in.light_clip);
    let hemi = mix(g.ground_bounce.rgb, g.sky_color.rgb, 0.5 + 0.5 * n.z);
    let lit = base * (hemi + sun * max(ndl, 0.0) + sun * max(-ndl, 0.0) * 0.45);
    return vec4<f32>(lit, 1.0);
}

// Lines (stem axes) and points (leaves) for trees seen from afar. Each is lit like what it
// replaces (a leaf by its normal, two-sided and translucent; a stem as a cylinder about its
// axis) and covers, through the samples it writes, the share of a pixel that its stems or
// leaves would: a 1-pixel line for a 0.3-pixel twig lights about one sample in four.
struct FlatOut {
    @builtin(position) clip: vec4<f32>,
    // rgb: the lit colour; a: the share of a pixel covered. Worked out per vertex: a far stem
    // or leaf spans a pixel or a few, and lighting each of its fragments (a dozen shadow-map
    // taps) would cost more than everything else a far tree draws.
    @location(0) lit: vec4<f32>,
    @location(1) world: vec3<f32>,
};

fn flat_vertex(position: vec3<f32>, size: f32, direction: vec4<f32>, i: Instance) -> FlatOut {
    var out: FlatOut;
    let world = placed(i, position);
    out.clip = g.view_proj * vec4<f32>(world, 1.0);
    let light_clip = g.light_view_proj * vec4<f32>(world, 1.0);
    let shade = flat_shade(world, turned(i, direction.xyz), vec3<f32>(size, i.stands_for.x, i.place.w), light_clip);
    out.lit = vec4<f32>(shade.lit, shade.cover);
    out.world = world;
    return out;
}

struct FlatColour {
    @location(0) colour: vec4<f32>,
    @builtin(sample_mask) mask: u32,
};

// A well-mixed 32-bit hash (PCG output permutation).
fn hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// How a line or point is lit, and the share of a pixel it covers.
struct FlatShade {
    lit: vec3<f32>,
    cover: f32,
};

// `size`: x metres of size, y items stood for, z the copy's scale.
fn flat_shade(world: vec3<f32>, direction: vec3<f32>, size: vec3<f32>, light_clip: vec4<f32>) -> FlatShade {
    let l = g.sun_dir.xyz;
    let sun = g.sun_color.rgb * sunlit(light_clip);
    let base = m.color.rgb;
    let to_eye = g.eye.xyz - world;
    let pixels_per_metre = g.eye.w * size.z / max(length(to_eye), 1e-3);
    var out: FlatShade;
    if (m.kind.x > 0.5) {
        // A leaf: two-sided, facing the eye.
        var n = normalize(direction);
        if (dot(n, to_eye) < 0.0) {
            n = -n;
        }
        let ndl = dot(n, l);
        let hemi = mix(g.ground_bounce.rgb, g.sky_color.rgb, 0.5 + 0.5 * n.z);
        out.lit = base * (hemi + sun * max(ndl, 0.0) + sun * max(-ndl, 0.0) * 0.45);
        out.cover = size.x * pixels_per_metre * pixels_per_metre * size.y;
    } else {
        // A stem: a cylinder about its axis, half of it towards the sun.
        let t = normalize(direction);
        let across = sqrt(max(1.0 - dot(t, l) * dot(t, l), 0.0));
        out.lit = base * (mix(g.ground_bounce.rgb, g.sky_color.rgb, 0.6) + sun * across * 0.5);
        out.cover = size.x * pixels_per_metre * size.y;
    }
    return out;
}

// Which of a pixel's 4 samples a line or point covers: that share of them, chosen afresh for
// each line or point so that overlapping ones fill a pixel as the leaves they stand for would
// (one fixed pattern per share would let them all land on the same samples); the share is
// rounded up or down at random, so that on average it is exact.
fn coverage_mask(cover: f32, seed: u32) -> u32 {
    let jitter = f32(seed & 0xffffu) / 65536.0;
    let samples = u32(clamp(floor(cover * 4.0 + jitter), 0.0, 4.0));
    let first = (seed >> 16u) & 3u;
    let run = (1u << samples) - 1u;
    return ((run << first) | (run >> (4u - first))) & 15u;
}

fn world_seed(world: vec3<f32>) -> u32 {
    return hash(bitcast<u32>(world.x) ^ hash(bitcast<u32>(world.y) ^ hash(bitcast<u32>(world.z))));
}

@fragment
fn fs_flat(in: FlatOut) -> FlatColour {
    return flat_colour(in);
}

fn flat_colour(in: FlatOut) -> FlatColour {
    var out: FlatColour;
    out.colour = vec4<f32>(in.lit.rgb, 1.0);
    out.mask = coverage_mask(in.lit.a, world_seed(in.world));
    return out;
}

// The same for OpenGL, which cannot write the sample mask: the fragment shader runs once per
// sample (the `sample` interpolation asks for that) and drops the samples outside the mask.
// The seed comes from the pixel and the primitive's first vertex, so every sample of a pixel
// draws the same mask.
struct FlatSampleOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) lit: vec4<f32>,
    @location(1) @interpolate(perspective, sample) world: vec3<f32>,
    @location(2) @interpolate(flat) seed_world: vec3<f32>,
};

fn per_sample(f: FlatOut) -> FlatSampleOut {
    var out: FlatSampleOut;
    out.clip = f.clip;
    out.lit = f.lit;
    out.world = f.world;
    out.seed_world = f.world;
    return out;
}

@fragment
fn fs_flat_per_sample(in: FlatSampleOut) -> @location(0) vec4<f32> {
    return flat_sample_colour(in);
}

fn flat_sample_colour(in: FlatSampleOut) -> vec4<f32> {
    let pixel = vec2<u32>(floor(in.clip.xy));
    let seed = world_seed(in.seed_world) ^ hash(pixel.x ^ hash(pixel.y));
    // The standard 4-sample pattern has one sample in each quarter of the pixel.
    let offset = fract(in.clip.xy);
    let sample = u32(offset.x * 2.0) + 2u * u32(offset.y * 2.0);
    if ((coverage_mask(in.lit.a, seed) & (1u << sample)) == 0u) {
        discard;
    }
    return vec4<f32>(in.lit.rgb, 1.0);
}

// Trees stored for range (sylva::lod::packed): each stem segment is two packed rings and each
// leaf a packed card, read as instances; the vertex shader rebuilds the triangles, lines and
// points the CPU's sylva::lod::expand makes, and the two must agree.

// The copy a draw places and the scales of its tree's records.
struct Copy {
    place: vec4<f32>,
    // x, y: cos and sin of the turn; z: how many stems or leaves each line or point stands
    // for; w: how much meshed leaves grow about their centres
    turn: vec4<f32>,
    // xyz: the records' box, lowest corner; w: the thickest radius
    lo: vec4<f32>,
    // xyz: the box's size; w: the longest leaf
    size: vec4<f32>,
    // stems: ring vertices, lobes, lobe depth; leaves: x the outline's area at unit size,
    // w the widest leaf
    run: vec4<f32>,
    // the copy's sway: the trunk's turn about x and y (radians), the trunk's length
    sway: vec4<f32>,
};

@group(2) @binding(0) var<uniform> copy: Copy;

struct SegmentIn {
    @location(8) a: vec4<u32>,
    @location(9) a_frame: u32,
    @location(10) b: vec4<u32>,
    @location(11) b_frame: u32,
};

struct CardIn {
    @location(8) at: vec4<u32>,
    @location(9) frame: u32,
};

fn copy_instance() -> Instance {
    var i: Instance;
    i.place = copy.place;
    i.turn = copy.turn.xy;
    i.stands_for = vec2<f32>(copy.turn.z, 0.0);
    return i;
}

// A unit quaternion from its three smallest components (10 bits each, 0..=1022 over
// -1/sqrt(2)..1/sqrt(2)) and the index of the largest (2 bits).
fn unpack_frame(bits: u32) -> vec4<f32> {
    let k = bits >> 30u;
    let raw = vec3<f32>(f32((bits >> 20u) & 1023u), f32((bits >> 10u) & 1023u), f32(bits & 1023u));
    let small = (raw / 1022.0 * 2.0 - 1.0) * 0.70710678;
    let largest = sqrt(max(1.0 - dot(small, small), 0.0));
    var q = vec4<f32>(small, largest);
    if (k == 0u) {
        q = vec4<f32>(largest, small.x, small.y, small.z);
    } else if (k == 1u) {
        q = vec4<f32>(small.x, largest, small.y, small.z);
    } else if (k == 2u) {
        q = vec4<f32>(small.x, small.y, largest, small.z);
    }
    return normalize(q);
}

fn rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

fn unpack_position(at: vec3<u32>) -> vec3<f32> {
    return copy.lo.xyz + vec3<f32>(at) / 65535.0 * copy.size.xyz;
}

struct Surface {
    position: vec3<f32>,
    normal: vec3<f32>,
};

// Where wind moves a point of the tree: sylva::lod::sway::Sway::displacement.
fn swayed(p: vec3<f32>) -> vec3<f32> {
    let length = copy.sway.z;
    if (length <= 0.0) {
        return p;
    }
    let s = max(p.z / length, 0.0);
    var along = s - 0.5;
    if (s <= 1.0) {
        along = s * s / 2.0;
    }
    let dx = length * copy.sway.y * along;
    let dy = -length * copy.sway.x * along;
    let dz = -(dx * dx + dy * dy) / (2.0 * max(p.z, 0.5));
    return p + vec3<f32>(dx, dy, dz);
}

// Vertex k of a segment's tube, k = 2 i + end for vertex i (0..=sides) of the near (end 0) or
// far (end 1) ring, as the shared index buffer numbers them: sylva::lod::expand::Tube::vertex.
fn tube_vertex(s: SegmentIn, k: u32) -> Surface {
    let i = k / 2u;
    let corner = vec2<u32>(0u, k % 2u);
    let centre_a = unpack_position(s.a.xyz);
    let centre_b = unpack_position(s.b.xyz);
    let radius_a = f32(s.a.w) / 65535.0 * copy.lo.w;
    let radius_b = f32(s.b.w) / 65535.0 * copy.lo.w;
    let length = distance(centre_a, centre_b);
    var slope = 0.0;
    if (length > 1e-9) {
        slope = (radius_b - radius_a) / length;
    }
    var q = unpack_frame(s.a_frame);
    var centre = centre_a;
    var r0 = radius_a;
    if (corner.y == 1u) {
        q = unpack_frame(s.b_frame);
        centre = centre_b;
        r0 = radius_b;
    }
    let x = rotate(q, vec3<f32>(1.0, 0.0, 0.0));
    let y = rotate(q, vec3<f32>(0.0, 1.0, 0.0));
    let z = rotate(q, vec3<f32>(0.0, 0.0, 1.0));
    let t = 6.2831853 * f32(i) / copy.run.x;
    let radial = x * cos(t) + y * sin(t);
    var r = r0;
    var in_plane = radial;
    let lobes = copy.run.y;
    if (lobes > 0.0) {
        r = r0 * (1.0 + copy.run.z * sin(lobes * t));
        let dr = r0 * copy.run.z * lobes * cos(lobes * t);
        let tangent = y * cos(t) - x * sin(t);
        let n = radial * r - tangent * dr;
        if (dot(n, n) > 0.0) {
            in_plane = normalize(n);
        }
    }
    var out: Surface;
    out.position = swayed(centre + radial * r);
    out.normal = in_plane - z * slope;
    return out;
}

struct Card {
    base: vec3<f32>,
    frame: vec4<f32>,
    length: f32,
    width: f32,
    shade: f32,
};

// sylva::lod::packed::Quantiser::unpack_leaf.
fn unpack_card(c: CardIn) -> Card {
    var out: Card;
    out.base = unpack_position(c.at.xyz);
    out.frame = unpack_frame(c.frame);
    out.length = f32(c.at.w & 63u) / 63.0 * copy.size.w;
    out.width = f32((c.at.w >> 6u) & 63u) / 63.0 * copy.run.w;
    out.shade = 0.3 + 0.7 * f32(c.at.w >> 12u) / 10.0;
    return out;
}

fn card_vertex(c: Card, position: vec3<f32>, normal: vec3<f32>) -> Surface {
    var out: Surface;
    let centre = vec3<f32>(0.0, 0.0, 0.5 * c.length);
    let at = position * vec3<f32>(c.width, c.width, c.length);
    out.position = swayed(c.base + rotate(c.frame, centre + (at - centre) * copy.turn.w));
    out.normal = rotate(c.frame, normal);
    return out;
}

fn surface_out(s: Surface, shade: f32) -> VsOut {
    return surface_vertex(s.position, s.normal, shade, copy_instance());
}

@vertex
fn vs_tube(@builtin(vertex_index) k: u32, s: SegmentIn) -> VsOut {
    return surface_out(tube_vertex(s, k), 1.0);
}

@vertex
fn vs_card(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, c: CardIn) -> VsOut {
    let card = unpack_card(c);
    return surface_out(card_vertex(card, position, normal), card.shade);
}

// A far stem or leaf in the tree's frame: where it is, its size, and its direction.
struct FlatItem {
    at: vec3<f32>,
    size: f32,
    direction: vec3<f32>,
};

// A far stem's line: vertex 0 at the near ring's centre, 1 at the far one's.
fn axis_item(k: u32, s: SegmentIn) -> FlatItem {
    let a = unpack_position(s.a.xyz);
    let b = unpack_position(s.b.xyz);
    var out: FlatItem;
    out.at = a;
    var radius = f32(s.a.w);
    if (k == 1u) {
        out.at = b;
        radius = f32(s.b.w);
    }
    out.direction = vec3<f32>(0.0, 0.0, 1.0);
    if (distance(a, b) > 0.0) {
        out.direction = normalize(b - a);
    }
    out.size = 2.0 * radius / 65535.0 * copy.lo.w;
    out.at = swayed(out.at);
    return out;
}

// A far leaf's point, at the middle of its blade, standing for the blade's area.
fn dot_item(c: CardIn) -> FlatItem {
    let card = unpack_card(c);
    var out: FlatItem;
    out.at = swayed(card.base + rotate(card.frame, vec3<f32>(0.0, 0.0, card.length * 0.5)));
    out.size = card.length * card.width * copy.run.x;
    out.direction = rotate(card.frame, vec3<f32>(0.0, 1.0, 0.0));
    return out;
}

fn item_vertex(f: FlatItem) -> FlatOut {
    return flat_vertex(f.at, f.size, vec4<f32>(f.direction, 0.0), copy_instance());
}

fn axis_vertex(k: u32, s: SegmentIn) -> FlatOut {
    return item_vertex(axis_item(k, s));
}

fn dot_vertex(c: CardIn) -> FlatOut {
    return item_vertex(dot_item(c));
}

@vertex
fn vs_axis(@builtin(vertex_index) k: u32, s: SegmentIn) -> FlatOut {
    return axis_vertex(k, s);
}

@vertex
fn vs_dot(c: CardIn) -> FlatOut {
    return dot_vertex(c);
}

@vertex
fn vs_axis_per_sample(@builtin(vertex_index) k: u32, s: SegmentIn) -> FlatSampleOut {
    return per_sample(axis_vertex(k, s));
}

@vertex
fn vs_dot_per_sample(c: CardIn) -> FlatSampleOut {
    return per_sample(dot_vertex(c));
}

fn shadow_clip(p: vec3<f32>) -> vec4<f32> {
    return g.light_view_proj * vec4<f32>(placed(copy_instance(), p), 1.0);
}

@vertex
fn vs_shadow_tube(@builtin(vertex_index) k: u32, s: SegmentIn) -> @builtin(position) vec4<f32> {
    return shadow_clip(tube_vertex(s, k).position);
}

@vertex
fn vs_shadow_card(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    c: CardIn,
) -> @builtin(position) vec4<f32> {
    return shadow_clip(card_vertex(unpack_card(c), position, normal).position);
}

@vertex
fn vs_shadow_axis(@builtin(vertex_index) k: u32, s: SegmentIn) -> @builtin(position) vec4<f32> {
    return shadow_clip(axis_item(k, s).at);
}

@vertex
fn vs_shadow_dot(c: CardIn) -> @builtin(position) vec4<f32> {
    return shadow_clip(dot_item(c).at);
}
