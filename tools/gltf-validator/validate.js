#!/usr/bin/env node
// Validates one glTF 2.0 asset (.gltf or .glb) with the Khronos glTF Validator and prints its
// report as JSON. Exit code: 0 without errors (warnings, infos and hints are allowed), 1 with
// errors, 2 when the file cannot be read or validated at all.
//
//   node tools/gltf-validator/validate.js asset.glb
//
// External resources (buffers, images) are read relative to the asset's folder.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

const file = process.argv[2];
if (!file || process.argv.length > 3) {
  console.error('usage: node validate.js FILE.gltf|FILE.glb');
  process.exit(2);
}

let bytes;
try {
  bytes = new Uint8Array(fs.readFileSync(file));
} catch (e) {
  console.error(`validate.js: cannot read ${file}: ${e.message}`);
  process.exit(2);
}

const dir = path.dirname(file);
validator
  .validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(dir, decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)),
        );
      }),
  })
  .then((report) => {
    console.log(JSON.stringify(report, null, 2));
    const n = report.issues.numErrors;
    console.error(
      `${file}: ${n} errors, ${report.issues.numWarnings} warnings, ` +
        `${report.issues.numInfos} infos, ${report.issues.numHints} hints (${report.validatorVersion})`,
    );
    process.exit(n > 0 ? 1 : 0);
  })
  .catch((e) => {
    console.error(`validate.js: ${file}: ${e}`);
    process.exit(2);
  });
