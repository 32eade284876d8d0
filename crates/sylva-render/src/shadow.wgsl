// The sun's shadow: where a point lies in the shadow map and how much sunlight reaches it.
// Appended to shader.wgsl (it reads the globals' shadow map); `cpu::shade` does the same.

// Taps of the shadow filter. The first 12: a golden-angle spiral filling the unit disc evenly,
// for surfaces whose shadows are seen whole (the ground, bark). The last 4: a square turned
// from the axes, for leaves: a leaf is a few pixels at most, lies among hundreds of others
// that break up its shadow anyway, and its fragments are most of a forest's, so it takes a
// third of the taps (each tap is itself a bilinear 2 x 2 comparison).
const TAPS = array<vec2<f32>, 16>(
    vec2<f32>(0.2041, 0.0000),
    vec2<f32>(-0.2607, 0.2388),
    vec2<f32>(0.0399, -0.4547),
    vec2<f32>(0.3286, 0.4286),
    vec2<f32>(-0.6030, -0.1067),
    vec2<f32>(0.5712, -0.3634),
    vec2<f32>(-0.1911, 0.7107),
    vec2<f32>(-0.3644, -0.7016),
    vec2<f32>(0.7906, 0.2887),
    vec2<f32>(-0.8224, 0.3395),
    vec2<f32>(0.3965, -0.8472),
    vec2<f32>(0.2930, 0.9341),
    vec2<f32>(0.6374, 0.2640),
    vec2<f32>(-0.2640, 0.6374),
    vec2<f32>(-0.6374, -0.2640),
    vec2<f32>(0.2640, -0.6374),
);
// Where a point lies in the shadow map: xy its texture coordinates, z its depth less the
// bias, w 1 where the map covers it.
fn shadow_point(light_clip: vec4<f32>) -> vec4<f32> {
    let p = light_clip.xyz / light_clip.w;
    let uv = vec2<f32>(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5);
    let inside = uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0 && p.z <= 1.0;
    return vec4<f32>(uv, p.z - g.shadow.y, select(0.0, 1.0, inside));
}

fn shadow_tap(s: vec4<f32>, i: u32) -> f32 {
    let offset = TAPS[i] * (3.0 * g.shadow.x);
    return textureSampleCompareLevel(shadow_map, shadow_sampler, s.xy + offset, s.z);
}

// Fraction of sunlight reaching a point: percentage-closer filtering over a disc three
// texels wide each way, so shadows on the ground have soft edges, as under a real sun (half
// a degree wide) and a crown's many small gaps. (The loops have constant bounds: llvmpipe
// runs a loop with bounds it cannot see per lane, at twice the cost.)
fn sunlit(light_clip: vec4<f32>) -> f32 {
    let s = shadow_point(light_clip);
    if (s.w == 0.0) {
        return 1.0;
    }
    var sum = 0.0;
    for (var i = 0u; i < 12u; i++) {
        sum += shadow_tap(s, i);
    }
    return sum / 12.0;
}

// `sunlit` for a leaf, through the last 4 taps.
fn sunlit_leaf(light_clip: vec4<f32>) -> f32 {
    let s = shadow_point(light_clip);
    if (s.w == 0.0) {
        return 1.0;
    }
    var sum = 0.0;
    for (var i = 12u; i < 16u; i++) {
        sum += shadow_tap(s, i);
    }
    return sum / 4.0;
}
