// Validates each GLB given on the command line with the Khronos glTF validator.
// Prints one line per file (errors, warnings, infos) and the messages of any error or warning;
// exits 1 if any file has an error.
//
// The validator does not check EXT_mesh_gpu_instancing (it reports it as unsupported), so a
// self-contained file that uses it is also read with three.js's GLTFLoader, as a web page
// would: every instanced node must come out as an InstancedMesh with as many finite copies as
// its accessors hold.
import { readFile } from "node:fs/promises";
import { dirname, resolve } from "node:path";
import validator from "gltf-validator";
import { Matrix4 } from "three";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";

/// The GLB's JSON chunk.
function jsonOf(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const length = view.getUint32(12, true);
  return JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + length)));
}

/// Problems three.js finds with a file's instanced nodes (none: an empty list).
async function instancingProblems(bytes) {
  const json = jsonOf(bytes);
  const wanted = (json.nodes ?? [])
    .map((n) => n.extensions?.EXT_mesh_gpu_instancing?.attributes)
    .filter(Boolean)
    .map((a) => json.accessors[a.TRANSLATION ?? a.ROTATION ?? a.SCALE].count);
  // Files of their own (shared meshes, impostors' atlases) are not fetched here: node has no
  // image decoder for three.js, and the validator above has read them.
  const external = [...(json.buffers ?? []), ...(json.images ?? [])].some((b) => b.uri !== undefined);
  if (wanted.length === 0 || external) return { read: false, problems: [] };
  const data = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  const gltf = await new GLTFLoader().parseAsync(data, "");
  const found = [];
  const m = new Matrix4();
  gltf.scene.traverse((o) => {
    if (!o.isInstancedMesh) return;
    let finite = true;
    for (let i = 0; i < o.count; i++) {
      o.getMatrixAt(i, m);
      finite &&= m.elements.every(Number.isFinite);
    }
    found.push({ count: o.count, finite });
  });
  const problems = [];
  const counts = (xs) => xs.slice().sort((a, b) => a - b).join(",");
  if (counts(found.map((f) => f.count)) !== counts(wanted)) {
    problems.push(`three.js made instanced meshes of ${counts(found.map((f) => f.count))} copies, the file has ${counts(wanted)}`);
  }
  if (found.some((f) => !f.finite)) problems.push("three.js placed a copy at a non-finite transform");
  return { read: true, copies: found.reduce((s, f) => s + f.count, 0), problems };
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node validate.mjs FILE.glb...");
  process.exit(2);
}
let failed = 0;
for (const file of files) {
  const bytes = new Uint8Array(await readFile(file));
  // Buffers in files of their own (a city tile's shared tree meshes) are read beside the GLB,
  // so their lengths and contents are checked too.
  const externalResourceFunction = (uri) =>
    readFile(resolve(dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b));
  const report = await validator.validateBytes(bytes, { maxIssues: 0, externalResourceFunction });
  const { numErrors, numWarnings, numInfos } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos`);
  for (const m of report.issues.messages.filter((m) => m.severity <= 1)) {
    console.log(`  ${m.severity === 0 ? "error" : "warning"} ${m.code} at ${m.pointer ?? ""}: ${m.message}`);
  }
  const instanced = await instancingProblems(bytes).catch((e) => ({ read: true, problems: [`three.js cannot read it: ${e}`] }));
  if (instanced.read) {
    console.log(`  three.js: ${instanced.copies ?? 0} instanced copies`);
    for (const p of instanced.problems) console.log(`  error ${p}`);
  }
  if (numErrors > 0 || instanced.problems.length > 0) failed++;
}
if (failed > 0) {
  console.error(`${failed} of ${files.length} files have glTF errors`);
  process.exit(1);
}
console.log(`all ${files.length} files valid`);
