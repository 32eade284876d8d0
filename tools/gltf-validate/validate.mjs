// Validates each GLB given on the command line with the Khronos glTF validator.
// Prints one line per file (errors, warnings, infos) and the messages of any error or warning;
// exits 1 if any file has an error.
import { readFile } from "node:fs/promises";
import { dirname, resolve } from "node:path";
import validator from "gltf-validator";

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
  if (numErrors > 0) failed++;
}
if (failed > 0) {
  console.error(`${failed} of ${files.length} files have glTF errors`);
  process.exit(1);
}
console.log(`all ${files.length} files valid`);
