// The parts of three.js (r187) and of NASA-AMMOS's 3d-tiles-renderer (0.5.3) that Sylva's city
// view uses, bundled with esbuild into one module so that both share one three.js: see
// crates/sylva-serve/assets/vendor/README.md.
export {
  AmbientLight, Box3, BufferAttribute, BufferGeometry, Cache, Color, DirectionalLight, Float32BufferAttribute, Frustum, Group,
  InstancedBufferAttribute, InstancedMesh,
  HemisphereLight, LineBasicMaterial, LineLoop, Matrix4, Mesh, MeshBasicMaterial,
  MeshLambertMaterial, PerspectiveCamera, PlaneGeometry, Points, PointsMaterial, Raycaster, SRGBColorSpace, Scene,
  TextureLoader, Vector2, Vector3, WebGLRenderer,
} from 'three';
export { MapControls } from 'three/examples/jsm/controls/MapControls.js';
export { TilesRenderer } from '3d-tiles-renderer/three';
export { GLTFExtensionsPlugin } from '3d-tiles-renderer/src/three/plugins/GLTFExtensionsPlugin.js';
