// The parts of three.js (r187) that Sylva's page uses, bundled and minified by esbuild:
// see crates/sylva-serve/assets/vendor/README.md.
export {
  BasicShadowMap, BoxGeometry, BufferAttribute, Color, DoubleSide, FrontSide, CylinderGeometry, DirectionalLight, Group, HemisphereLight, Mesh,
  MeshLambertMaterial, PCFSoftShadowMap, PerspectiveCamera, PlaneGeometry, SRGBColorSpace,
  Scene, SphereGeometry, Vector2, Vector3, WebGLRenderer,
} from 'three';
export { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
