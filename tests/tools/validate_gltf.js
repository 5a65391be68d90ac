#!/usr/bin/env node
// The Khronos glTF validator (npm package gltf-validator) on one .glb or .gltf file, its
// external buffers loaded from beside it. Prints the report's issues; exits 0 when there are no
// errors and no warnings, 1 when there are, 2 when the file or the package cannot be loaded.
// Found as a global npm package or in NODE_PATH (app/install-deps.sh installs it globally).
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  try {
    const root = require('child_process').execSync('npm root -g', {stdio: ['ignore', 'pipe', 'ignore']}).toString().trim();
    validator = require(path.join(root, 'gltf-validator'));
  } catch (e2) {
    console.error('validate_gltf: the npm package gltf-validator is not installed (npm install -g gltf-validator)');
    process.exit(2);
  }
}

const file = process.argv[2];
if (!file) {
  console.error('usage: validate_gltf.js FILE.glb|FILE.gltf');
  process.exit(2);
}
let bytes;
try {
  bytes = new Uint8Array(fs.readFileSync(file));
} catch (e) {
  console.error('validate_gltf: ' + file + ': ' + e.message);
  process.exit(2);
}
validator.validateBytes(bytes, {
  uri: path.basename(file),
  maxIssues: 0,
  externalResourceFunction: (uri) => new Promise((resolve, reject) => {
    fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) => {
      if (err) reject(err.toString()); else resolve(new Uint8Array(data));
    });
  }),
}).then((report) => {
  const i = report.issues;
  for (const m of i.messages) console.log(`${m.severity === 0 ? 'error' : m.severity === 1 ? 'warning' : m.severity === 2 ? 'info' : 'hint'}: ${m.code} ${m.pointer || ''} ${m.message}`);
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
  process.exit(i.numErrors === 0 && i.numWarnings === 0 ? 0 : 1);
}, (error) => {
  console.error('validate_gltf: ' + file + ': ' + error);
  process.exit(2);
});
