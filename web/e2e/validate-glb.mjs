// Runs the Khronos glTF validator on one .glb file and prints its issue counts and messages
// as one line of JSON, for the library's tests: node web/e2e/validate-glb.mjs FILE.glb
import { readFileSync } from 'node:fs';
import validator from 'gltf-validator';

const file = process.argv[2];
const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
  maxIssues: 100,
});
const severity = ['error', 'warning', 'info', 'hint'];
const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
console.log(
  JSON.stringify({
    numErrors,
    numWarnings,
    numInfos,
    numHints,
    messages: messages.map(
      (m) => `${severity[m.severity] ?? m.severity} ${m.code} ${m.pointer ?? ''}: ${m.message}`,
    ),
  }),
);
