// Impostors, and the dissolve between a tree stored for range and its impostor. Appended to
// shader.wgsl (it uses its globals, `copy`, `hash`, `swayed` and the fragment shaders' colour
// functions); `crate::impostor` bakes the atlas and `cpu::impostor` draws the same on the CPU.

// An impostor's copy entry (`Copy`): `place`, `turn.xy` and `sway` as a stored tree's;
// `lo`: the cell's texels (left column, top row of view 0, width) and the half width it spans,
// metres; `size.xy`: the lowest and highest point it spans, metres. `sway.w` is the share of
// pixels the impostor draws (and its tree's draws give up) while one dissolves into the other.

@group(3) @binding(0) var atlas: texture_2d<f32>;
@group(3) @binding(1) var atlas_sampler: sampler;

// Views round each tree in the atlas (`crate::impostor::VIEWS`), and texel rows per view
// (`CELL`).
const VIEWS: u32 = 8u;
const CELL: f32 = 64.0;

// Two thresholds in 0..1 for a pixel, the same in every frame: x for the dissolve, y for the
// impostor's alpha. A fixed pattern per pixel means a tree and its impostor take
// complementary pixels, and the CPU's `shade::dither` picks the same ones.
fn dither(clip: vec4<f32>) -> vec2<f32> {
    let pixel = vec2<u32>(floor(clip.xy));
    let h = hash(pixel.x ^ hash(pixel.y + 0x9e3779b9u));
    return vec2<f32>(f32(h & 0xffffu), f32(h >> 16u)) / 65536.0;
}

// A tree's draws while it dissolves: the pixels its impostor has taken are dropped.
fn fade_out(clip: vec4<f32>) {
    if (dither(clip).x < copy.sway.w) {
        discard;
    }
}

@fragment
fn fs_main_fading(in: VsOut) -> @location(0) vec4<f32> {
    fade_out(in.clip);
    return main_colour(in);
}

@fragment
fn fs_leaf_fading(in: VsOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    fade_out(in.clip);
    return leaf_colour(in, front);
}

@fragment
fn fs_flat_fading(in: FlatOut) -> FlatColour {
    fade_out(in.clip);
    return flat_colour(in);
}

@fragment
fn fs_flat_per_sample_fading(in: FlatSampleOut) -> @location(0) vec4<f32> {
    fade_out(in.clip);
    return flat_sample_colour(in);
}

struct ImpostorOut {
    @builtin(position) clip: vec4<f32>,
    // Texels of the two views either side of the eye.
    @location(0) first: vec2<f32>,
    @location(1) second: vec2<f32>,
    @location(2) @interpolate(flat) weight: f32,
};

// One quad per copy, standing on the trunk's axis and turned about it to face the eye (the
// views were taken level; from above the canopy the quad leans with the sway alone).
@vertex
fn vs_impostor(@builtin(vertex_index) k: u32) -> ImpostorOut {
    let corners = array<vec2<f32>, 6>(
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0),
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 1.0), vec2<f32>(0.0, 1.0),
    );
    let corner = corners[k];
    let i = copy_instance();
    var towards = g.eye.xy - i.place.xy;
    if (length(towards) < 1e-4) {
        towards = vec2<f32>(0.0, -1.0);
    }
    towards = normalize(towards);
    // The picture's right as the eye sees it, in the tree's own frame (its turn undone).
    let right = vec2<f32>(-towards.y, towards.x);
    let c = i.turn;
    let own_right = vec3<f32>(c.x * right.x + c.y * right.y, -c.y * right.x + c.x * right.y, 0.0);
    let cell = copy.lo;
    let p = own_right * ((2.0 * corner.x - 1.0) * cell.w) + vec3<f32>(0.0, 0.0, mix(copy.size.x, copy.size.y, corner.y));
    var out: ImpostorOut;
    out.clip = g.view_proj * vec4<f32>(placed(i, swayed(p)), 1.0);
    // The views are taken in the world's frame, lit by the sun, so they are chosen by where
    // the eye is in the world (`sylva::lod::view_blend`), whatever the copy's turn.
    let t = fract(atan2(towards.x, -towards.y) / 6.2831853) * f32(VIEWS);
    let first = min(u32(floor(t)), VIEWS - 1u);
    out.weight = clamp(t - f32(first), 0.0, 1.0);
    // From the centre of the cell's first texel to that of its last, so that the filter
    // never reads the next cell or view.
    let x = cell.x + 0.5 + corner.x * (cell.z - 1.0);
    let y = cell.y + 0.5 + (1.0 - corner.y) * (CELL - 1.0);
    out.first = vec2<f32>(x, y + f32(first) * CELL);
    out.second = vec2<f32>(x, y + f32((first + 1u) % VIEWS) * CELL);
    return out;
}

// The two views cross-faded; a pixel is drawn where its alpha passes its
// threshold (so a half-covered texel covers half the pixels) and where the dissolve gives it
// to the impostor.
@fragment
fn fs_impostor(in: ImpostorOut) -> @location(0) vec4<f32> {
    let d = dither(in.clip);
    if (d.x >= copy.sway.w) {
        discard;
    }
    let size = vec2<f32>(textureDimensions(atlas));
    let a = textureSampleLevel(atlas, atlas_sampler, in.first / size, 0.0);
    let b = textureSampleLevel(atlas, atlas_sampler, in.second / size, 0.0);
    // The atlas holds colour times cover: filtered and cross-faded so, then divided by the
    // cover, a texel's colour counts by how much of it the tree covered.
    let c = mix(a, b, in.weight);
    if (c.a <= d.y) {
        discard;
    }
    return vec4<f32>(c.rgb / c.a, 1.0);
}
