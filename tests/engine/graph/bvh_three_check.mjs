// Parses a BVH file with three.js's BVHLoader (a reader motifmine did not write) and prints
// "frames=F bones=B": the root position track's keyframes and the skeleton's bones.
// usage: node bvh_three_check.mjs NPM_PREFIX FILE.bvh   (three installed under NPM_PREFIX)
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { join } from 'node:path';

const [prefix, file] = process.argv.slice(2);
const { BVHLoader } = await import(
  pathToFileURL(join(prefix, 'node_modules/three/examples/jsm/loaders/BVHLoader.js')).href);
const result = new BVHLoader().parse(readFileSync(file, 'utf8'));
const position = result.clip.tracks.find((track) => track.name.endsWith('.position'));
console.log(`frames=${position.times.length} bones=${result.skeleton.bones.length}`);
