// What the street page and the city view both ask of the browser's WebGL.

// Whether this browser draws WebGL without a graphics card: it names a software renderer
// (SwiftShader, llvmpipe, lavapipe), or refuses a context that asks to fail on a major
// performance caveat (which a browser told to ignore its GPU blocklist does not).
export function softwareGl() {
  const probe = document.createElement('canvas');
  const gl = probe.getContext('webgl2', { failIfMajorPerformanceCaveat: true });
  if (!gl) return true;
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|lavapipe|softpipe|software/i.test(name);
}
