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
};

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) light_clip: vec4<f32>,
};

@vertex
fn vs_main(v: VsIn) -> VsOut {
    var out: VsOut;
    out.clip = g.view_proj * vec4<f32>(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.light_clip = g.light_view_proj * vec4<f32>(v.position, 1.0);
    return out;
}

@vertex
fn vs_shadow(v: VsIn) -> @builtin(position) vec4<f32> {
    return g.light_view_proj * vec4<f32>(v.position, 1.0);
}

// Fraction of sunlight reaching a point: 3x3 percentage-closer filtering.
fn sunlit(light_clip: vec4<f32>) -> f32 {
    let p = light_clip.xyz / light_clip.w;
    let uv = vec2<f32>(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5);
    if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0 || p.z > 1.0) {
        return 1.0;
    }
    var sum = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let offset = vec2<f32>(f32(dx), f32(dy)) * g.shadow.x;
            sum += textureSampleCompareLevel(shadow_map, shadow_sampler, uv + offset, p.z - g.shadow.y);
        }
    }
    return sum / 9.0;
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

@fragment
fn fs_main(in: VsOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    let kind = m.kind.x;
    var n = normalize(in.normal);
    var base = m.color.rgb;
    if (kind > 1.5) {
        // Fade the grid out with distance so it never shimmers into noise.
        base = mix(base, base * 0.55, grid(in.world.xy));
    }
    if (kind > 0.5 && kind < 1.5 && !front) {
        n = -n;
    }
    let l = g.sun_dir.xyz;
    let ndl = dot(n, l);
    let sun = g.sun_color.rgb * sunlit(in.light_clip);
    // Sky from above, light bounced off the ground from below.
    let hemi = mix(g.ground_bounce.rgb, g.sky_color.rgb, 0.5 + 0.5 * n.z);
    var lit = base * (hemi + sun * max(ndl, 0.0));
    if (kind > 0.5 && kind < 1.5) {
        // Light through the leaf when the sun is behind it.
        lit += base * sun * max(-ndl, 0.0) * 0.45;
    }
    return vec4<f32>(lit, 1.0);
}

// Lines (stem axes) and points (leaves) for trees seen from afar: no normals, so they take the
// sky light and an average share of the sun.
struct FlatOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) light_clip: vec4<f32>,
};

@vertex
fn vs_flat(@location(0) position: vec3<f32>) -> FlatOut {
    var out: FlatOut;
    out.clip = g.view_proj * vec4<f32>(position, 1.0);
    out.light_clip = g.light_view_proj * vec4<f32>(position, 1.0);
    return out;
}

@fragment
fn fs_flat(in: FlatOut) -> @location(0) vec4<f32> {
    let sun = g.sun_color.rgb * sunlit(in.light_clip) * 0.45;
    let lit = m.color.rgb * (g.sky_color.rgb * 0.7 + sun);
    return vec4<f32>(lit, 1.0);
}
