// Runs the Khronos glTF Validator on each file named on the command line and prints one JSON
// line per file: {"file", "errors", "warnings", "infos", "hints", "issues": [errors and warnings]}.
// GLTF_VALIDATOR names the folder holding node_modules/gltf-validator.
const fs = require('fs');
const path = require('path');
const validator = require(path.join(process.env.GLTF_VALIDATOR, 'node_modules', 'gltf-validator'));

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 1000,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)),
                  (err, data) => err ? reject(err.toString()) : resolve(new Uint8Array(data)));
    }),
  });
  const i = report.issues;
  return {file, errors: i.numErrors, warnings: i.numWarnings, infos: i.numInfos, hints: i.numHints,
          issues: i.messages.filter((m) => m.severity <= 1).map((m) => `${m.code} ${m.pointer || ''}: ${m.message}`)};
}

(async () => {
  for (const file of process.argv.slice(2)) {
    try {
      console.log(JSON.stringify(await validate(file)));
    } catch (e) {
      console.log(JSON.stringify({file, errors: -1, warnings: -1, issues: ['validator failed: ' + e]}));
    }
  }
})();
