#!/usr/bin/env node
// Runs the Khronos glTF validator on .glb/.gltf files; prints every error and warning and
// exits 1 if there is any (2 if the validator is missing or a file cannot be read).
// Usage: node tests/validator/validate.js FILE [FILE...]
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('validate.js: the Khronos glTF validator (npm package gltf-validator) is not ' +
                'installed in tests/validator/node_modules; run: bash tools/setup.sh --test');
  process.exit(2);
}

async function validate(file) {
  const data = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(data, {
    uri: path.basename(file),
    maxIssues: 1000,
    externalResourceFunction: (uri) =>
      Promise.reject(new Error('external resource not allowed: ' + uri)),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ` +
              `${i.numInfos} infos, ${i.numHints} hints (validator ${report.validatorVersion})`);
  for (const m of i.messages) {
    if (m.severity <= 1) {
      console.log(`  ${m.severity === 0 ? 'ERROR' : 'WARNING'} ${m.code} ` +
                  `${m.pointer || ''}: ${m.message}`);
    }
  }
  return i.numErrors + i.numWarnings;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: node validate.js FILE.glb|FILE.gltf ...');
    process.exit(2);
  }
  let bad = 0;
  for (const f of files) {
    try {
      bad += await validate(f);
    } catch (e) {
      console.error(`validate.js: ${f}: ${e.message || e}`);
      process.exit(2);
    }
  }
  process.exit(bad > 0 ? 1 : 0);
})();
