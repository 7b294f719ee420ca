#!/usr/bin/env node
// Loads an exported .glb/.vrm with three.js (GLTFLoader, and @pixiv/three-vrm for .vrm) the
// way a web app would, and checks what a rigger relies on. Exit 1 on any failed check.
// usage: node check_export.mjs FILE --height H [--joints N] [--targets N] [--vrm] [--uv]
//        [--bone NAME]... [--target NAME]...   (bones and morph targets that must exist)
//        [--no-geometry]    (a test fixture, not a body: skip the T-pose and facing checks)
//        [--materials a,b]  (the skinned meshes' materials, by name, in order)
//        [--morph-normals]  (every morph target carries normal deltas)
//        [--look-at]        (.vrm: a VRM lookAt of type bone, on the eye bones)
import fs from 'node:fs';
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const args = process.argv.slice(2);
const file = args[0];
const opt = (name) => {
  const i = args.indexOf('--' + name);
  return i < 0 ? undefined : args[i + 1];
};
const geometry = !args.includes('--no-geometry');
const bones_wanted = args.flatMap((a, i) => (a === '--bone' ? [args[i + 1]] : []));
const targets_wanted = args.flatMap((a, i) => (a === '--target' ? [args[i + 1]] : []));
let failures = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
};

const loader = new GLTFLoader();
const vrm_mode = args.includes('--vrm');
if (vrm_mode) {
  const { VRMLoaderPlugin } = await import('@pixiv/three-vrm');
  loader.register((parser) => new VRMLoaderPlugin(parser));
}
const bytes = fs.readFileSync(file);
const data = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new Promise((resolve, reject) => loader.parse(data, '', resolve, reject));
const scene = gltf.scene;
scene.updateMatrixWorld(true);

let mesh = null;
scene.traverse((o) => {
  if (o.isSkinnedMesh && !mesh) mesh = o;
});
check(mesh !== null, `${file}: a skinned mesh`);
if (!mesh) process.exit(1);
const bones = mesh.skeleton.bones;
console.log(`     ${bones.length} bones, ${mesh.geometry.attributes.position.count} vertices, ` +
            `${Object.keys(mesh.morphTargetDictionary || {}).length} morph targets`);
if (opt('joints')) check(bones.length === Number(opt('joints')), `bones = ${opt('joints')}`);
for (const name of bones_wanted) {
  check(bones.some((b) => b.name === name), `bone '${name}' present`);
}

if (args.includes('--uv')) {
  const uv = mesh.geometry.attributes.uv;
  check(uv !== undefined && uv.count === mesh.geometry.attributes.position.count,
        'texture coordinates (TEXCOORD_0) on every vertex');
}

if (opt('materials')) {
  const names = [];
  scene.traverse((o) => {
    if (o.isSkinnedMesh) names.push(o.material.name);
  });
  check(names.join(',') === opt('materials'), `materials ${names.join(',')} = ${opt('materials')}`);
}
if (args.includes('--morph-normals')) {
  const n = (mesh.geometry.morphAttributes.normal || []).length;
  const p = (mesh.geometry.morphAttributes.position || []).length;
  check(p > 0 && n === p, `normal deltas on every morph target (${n} of ${p})`);
}

// Morph dictionary: the expected count, every influence at 0 (the base mesh is the design).
const dict = mesh.morphTargetDictionary || {};
const influences = mesh.morphTargetInfluences || [];
if (opt('targets')) {
  check(Object.keys(dict).length === Number(opt('targets')), `morph targets = ${opt('targets')}`);
}
check(influences.every((w) => w === 0), 'every morph influence is 0 by default');
for (const name of targets_wanted) check(name in dict, `morph target '${name}' present`);

// Height of the skinned mesh at zero weights (skeleton and mesh agree: bind pose = identity).
const skinned_height = () => {
  mesh.skeleton.update();
  const v = new THREE.Vector3();
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < mesh.geometry.attributes.position.count; i++) {
    mesh.getVertexPosition(i, v);
    v.applyMatrix4(mesh.matrixWorld);
    lo = Math.min(lo, v.y);
    hi = Math.max(hi, v.y);
  }
  return [lo, hi];
};
const [lo, hi] = skinned_height();
console.log(`     skinned mesh at zero weights: y from ${lo.toFixed(5)} to ${hi.toFixed(5)} m`);
if (opt('height')) {
  const h = Number(opt('height'));
  check(Math.abs(hi - lo - h) < 2e-4, `height ${(hi - lo).toFixed(4)} m = measure's ${h} m`);
  check(Math.abs(lo) < 1e-4, 'feet on the ground (lowest vertex at y = 0)');
}

// Every bone with one child points its local +Y at that child (Blender's bone axis).
let worst = 0, worst_name = '';
const p = new THREE.Vector3(), c = new THREE.Vector3(), axis = new THREE.Vector3();
for (const b of bones) {
  const kids = b.children.filter((k) => k.isBone);
  if (kids.length !== 1) continue;
  b.getWorldPosition(p);
  kids[0].getWorldPosition(c);
  if (c.distanceTo(p) < 1e-6) continue;  // coincident joints: no direction to check
  const dir = c.sub(p).normalize();
  axis.set(0, 1, 0).transformDirection(b.matrixWorld);
  const deg = THREE.MathUtils.radToDeg(Math.acos(Math.min(1, axis.dot(dir))));
  if (deg > worst) [worst, worst_name] = [deg, b.name];
}
check(worst < 1, `bones point at their child (worst ${worst.toFixed(3)} deg at '${worst_name}')`);

// A shape key changes the body (the targets are live).
const first = Object.keys(dict).find((k) => k.startsWith('shape_'));
if (first !== undefined) {
  influences[dict[first]] = 1;
  const [lo2, hi2] = skinned_height();
  influences[dict[first]] = 0;
  let moved = 0;
  const a = new THREE.Vector3(), b2 = new THREE.Vector3();
  // A morph moves vertices: compare one vertex with and without.
  mesh.getVertexPosition(0, a);
  influences[dict[first]] = 1;
  mesh.getVertexPosition(0, b2);
  influences[dict[first]] = 0;
  moved = a.distanceTo(b2) + Math.abs(hi2 - lo2 - (hi - lo));
  check(moved > 1e-4, `'${first}' at weight 1 changes the body (${moved.toFixed(4)} m)`);
}

if (vrm_mode) {
  const vrm = gltf.userData.vrm;
  check(vrm !== undefined, 'three-vrm found a VRM');
  if (vrm) {
    check(vrm.meta && vrm.meta.metaVersion === '1', `VRM 1.0 meta (name '${vrm.meta && vrm.meta.name}')`);
    const expect = {
      hips: 'pelvis', spine: 'spine1', chest: 'spine2', upperChest: 'spine3', neck: 'neck',
      head: 'head', leftShoulder: 'left_collar', leftUpperArm: 'left_shoulder',
      leftLowerArm: 'left_elbow', leftHand: 'left_wrist', rightShoulder: 'right_collar',
      rightUpperArm: 'right_shoulder', rightLowerArm: 'right_elbow', rightHand: 'right_wrist',
      leftUpperLeg: 'left_hip', leftLowerLeg: 'left_knee', leftFoot: 'left_ankle',
      leftToes: 'left_foot', rightUpperLeg: 'right_hip', rightLowerLeg: 'right_knee',
      rightFoot: 'right_ankle', rightToes: 'right_foot',
    };
    // SMPL+H / SMPL-X: fingers (thumb1 is VRM's metacarpal), SMPL-X: jaw and eyes.
    if (bones.some((b) => b.name === 'left_index1')) {
      Object.assign(expect, {
        leftIndexProximal: 'left_index1', leftIndexDistal: 'left_index3',
        leftThumbMetacarpal: 'left_thumb1', rightLittleIntermediate: 'right_pinky2',
        rightRingProximal: 'right_ring1', rightMiddleDistal: 'right_middle3',
      });
    }
    if (bones.some((b) => b.name === 'jaw')) {
      Object.assign(expect, { jaw: 'jaw', leftEye: 'left_eye_smplhf', rightEye: 'right_eye_smplhf' });
    }
    for (const [role, joint] of Object.entries(expect)) {
      const node = vrm.humanoid.getRawBoneNode(role);
      check(node && node.name === joint, `humanoid ${role} = ${joint}`);
    }
    if (args.includes('--look-at')) {
      const look = vrm.lookAt;
      check(look && look.applier && look.applier.constructor.type === 'bone',
            `lookAt of type bone (${look && look.applier && look.applier.constructor.type})`);
      if (look) {
        // The origin between the eyes: in front of and above the head joint.
        const origin = look.getLookAtWorldPosition(new THREE.Vector3());
        const head = vrm.humanoid.getRawBoneNode('head').getWorldPosition(new THREE.Vector3());
        const eye = vrm.humanoid.getRawBoneNode('leftEye').getWorldPosition(new THREE.Vector3());
        check(Math.abs(origin.y - eye.y) < 2e-3 && origin.z > head.z && Math.abs(origin.x) < 2e-3,
              `lookAt origin between the eyes (${origin.toArray().map((v) => v.toFixed(3))})`);
      }
    }
  }
  if (vrm && geometry) {
    // T-pose: hands level with the upper arms, out to the sides; facing +Z (toes in front).
    const wp = (role) => vrm.humanoid.getRawBoneNode(role).getWorldPosition(new THREE.Vector3());
    for (const side of ['left', 'right']) {
      const s = wp(side + 'UpperArm'), h = wp(side + 'Hand');
      check(Math.abs(h.y - s.y) < 1e-3 && Math.abs(h.x - s.x) > 0.3,
            `T-pose: ${side} hand level with the shoulder (dy ${(h.y - s.y).toFixed(4)} m)`);
    }
    check(wp('leftToes').z > wp('leftFoot').z, 'facing +Z (toes in front of the ankle)');
    check(wp('leftUpperArm').x > 0, "the avatar's left is +X (seen from the front, on the right)");
  }
}
process.exit(failures > 0 ? 1 : 0);
