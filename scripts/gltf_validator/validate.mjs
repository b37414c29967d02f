// Validates a .glb or .gltf with the Khronos glTF-Validator (npm package gltf-validator).
// usage: node validate.mjs MODEL.glb
// Prints the issues (code, severity, where, message) and a last line
//   errors=N warnings=N infos=N hints=N
// Exit status: 0 when there are no errors and no warnings, 1 otherwise, 2 when the file cannot be read.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const file = process.argv[2];
if (!file) {
  console.error('usage: node validate.mjs MODEL.glb|MODEL.gltf');
  process.exit(2);
}
let bytes;
try {
  bytes = new Uint8Array(await readFile(file));
} catch (error) {
  console.error(`${file}: ${error.message}`);
  process.exit(2);
}
const report = await validator.validateBytes(bytes, {
  uri: path.basename(file),
  maxIssues: 1000,
  // External resources (a .gltf's .bin or images) are read relative to the model.
  externalResourceFunction: (uri) =>
    readFile(path.join(path.dirname(file), decodeURIComponent(uri))).then((data) => new Uint8Array(data)),
});
const severities = ['error', 'warning', 'info', 'hint'];
for (const message of report.issues.messages) {
  console.log(`${severities[message.severity]} ${message.code} ${message.pointer ?? ''}: ${message.message}`);
}
const issues = report.issues;
console.log(`errors=${issues.numErrors} warnings=${issues.numWarnings} infos=${issues.numInfos} hints=${issues.numHints}`);
process.exit(issues.numErrors === 0 && issues.numWarnings === 0 ? 0 : 1);
