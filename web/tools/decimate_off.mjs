// Decimates an OFF triangle mesh with meshoptimizer's simplifier (quadric error, topology kept)
// and writes an OFF: how web/assets/bunny_blue_jewel.glb was made small enough to commit
// (docs/web.md has the command). Usage: node tools/decimate_off.mjs IN.off OUT.off TRIANGLES
import { readFileSync, writeFileSync, renameSync } from 'node:fs';
import { MeshoptSimplifier } from 'meshoptimizer';

const [input, output, wanted] = process.argv.slice(2);
if (!input || !output || !(Number(wanted) > 0)) {
  console.error('usage: node tools/decimate_off.mjs IN.off OUT.off TRIANGLES');
  process.exit(2);
}
const words = readFileSync(input, 'utf8').replace(/#.*$/gm, '').split(/\s+/).filter((w) => w.length > 0);
if (words[0] !== 'OFF') throw new Error(`${input}: not an OFF file (no OFF header)`);
const vertexCount = Number(words[1]), faceCount = Number(words[2]);
const positions = new Float32Array(vertexCount * 3);
let at = 4;
for (let i = 0; i < vertexCount * 3; ++i) positions[i] = Number(words[at++]);
const indices = [];
for (let f = 0; f < faceCount; ++f) {
  const n = Number(words[at++]);
  const face = words.slice(at, at + n).map(Number);
  at += n;
  for (let k = 1; k + 1 < n; ++k) indices.push(face[0], face[k], face[k + 1]);  // fan
}
await MeshoptSimplifier.ready;
const [simplified, error] = MeshoptSimplifier.simplify(new Uint32Array(indices), positions, 3,
                                                       3 * Number(wanted), 0.05, []);
// Only the vertices the simplified triangles use, in first-use order.
const remap = new Map();
const kept = [];
const faces = [];
for (const i of simplified) {
  if (!remap.has(i)) remap.set(i, remap.size), kept.push(i);
  faces.push(remap.get(i));
}
const lines = ['OFF', `${kept.length} ${faces.length / 3} 0`];
for (const i of kept) lines.push(`${positions[3 * i]} ${positions[3 * i + 1]} ${positions[3 * i + 2]}`);
for (let t = 0; t < faces.length; t += 3) lines.push(`3 ${faces[t]} ${faces[t + 1]} ${faces[t + 2]}`);
writeFileSync(output + '.tmp', lines.join('\n') + '\n');
renameSync(output + '.tmp', output);
console.log(`${input}: ${faceCount} triangles -> ${faces.length / 3}, ${kept.length} vertices ` +
            `(relative error ${error.toExponential(2)})`);
