// Lights given as Jade gives them to `jade render --light` (docs/web.md): {type: 'dir', vector:
// towards the light, color: irradiance E} or {type: 'point', vector: position, color: intensity},
// linear RGB, as three.js lights whose colour × intensity is that value (three.js's
// DirectionalLight shines from its position towards its target, here the origin).
import { DirectionalLight, PointLight } from 'three';

export function makeLight({ type, vector, color }) {
  const light = type === 'point' ? new PointLight(0xffffff, 1, 0, 2) : new DirectionalLight(0xffffff, 1);
  if (type !== 'point' && type !== 'dir') throw new Error(`light type '${type}' is not dir or point`);
  light.color.setRGB(color[0], color[1], color[2]);  // linear (three.js's working colour space)
  light.position.set(vector[0], vector[1], vector[2]);
  return light;
}
