import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const q = new URLSearchParams(location.search);
const W = Number(q.get('w') ?? 240), H = Number(q.get('h') ?? 280), T = Number(q.get('t') ?? 0);
const out = document.getElementById('result');

try {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(W, H);
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace;  // facerender writes linear values
  document.body.prepend(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color().setRGB(0.93, 0.94, 0.96, THREE.LinearSRGBColorSpace);
  // facemesh render.cpp: light = 0.22 + 0.68·max(0, n·key) + 0.22·max(0, n·fill); three's Lambert
  // BRDF divides by π, so the intensities are multiplied by π.
  scene.add(new THREE.AmbientLight(0xffffff, 0.22 * Math.PI));
  const key = new THREE.DirectionalLight(0xffffff, 0.68 * Math.PI);
  key.position.set(-0.35, 0.55, 0.75);
  const fill = new THREE.DirectionalLight(0xffffff, 0.22 * Math.PI);
  fill.position.set(0.6, 0.1, 0.5);
  scene.add(key, fill);
  // RenderOptions defaults: vertical field of view 0.35 rad, 0.75 m from the target (0, −0.01, 0)
  const camera = new THREE.PerspectiveCamera(0.35 * 180 / Math.PI, W / H, 0.01, 10);
  camera.position.set(0, -0.01, 0.75);
  camera.lookAt(0, -0.01, 0);

  const gltf = await new GLTFLoader().loadAsync(q.get('glb'));
  // every mesh (the skin "face", the eyeballs under "eye_r"/"eye_l", the lower teeth under "jaw")
  // shaded like facerender: Lambert on the vertex colours, a flat dark colour on back faces
  const face = gltf.scene.getObjectByName('face');
  const mesh = face.isMesh ? face : face.children.find((c) => c.isMesh);
  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  for (const m of meshes) {
    m.material = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.FrontSide });
    const back = new THREE.Mesh(m.geometry, new THREE.MeshBasicMaterial({
      color: new THREE.Color().setRGB(0.18, 0.07, 0.07, THREE.LinearSRGBColorSpace), side: THREE.BackSide }));
    back.morphTargetInfluences = m.morphTargetInfluences;
    back.morphTargetDictionary = m.morphTargetDictionary;
    m.add(back);  // a child: it inherits the node transform (pivot offsets, eye and jaw rotations)
  }
  scene.add(gltf.scene);
  const mixer = new THREE.AnimationMixer(gltf.scene);
  const action = mixer.clipAction(gltf.animations[0]);
  action.setLoop(THREE.LoopOnce, 1);  // t = the clip's end must show the last key, not wrap to 0
  action.clampWhenFinished = true;
  action.play();
  mixer.setTime(T);
  renderer.render(scene, camera);

  const gl = renderer.getContext();
  const px = new Uint8Array(W * H * 4);
  gl.readPixels(0, 0, W, H, gl.RGBA, gl.UNSIGNED_BYTE, px);
  const img = new Image();
  img.src = q.get('ref');
  await img.decode();
  const c = document.createElement('canvas');
  c.width = W;
  c.height = H;
  const ctx = c.getContext('2d');
  ctx.drawImage(img, 0, 0);
  const ref = ctx.getImageData(0, 0, W, H).data;
  let sum = 0, fg = 0;
  for (let y = 0; y < H; ++y) {
    for (let x = 0; x < W; ++x) {
      const a = ((H - 1 - y) * W + x) * 4, b = (y * W + x) * 4;  // WebGL rows are bottom-up
      for (let k = 0; k < 3; ++k) sum += Math.abs(px[a + k] - ref[b + k]);
      if (Math.abs(ref[b] - 237) + Math.abs(ref[b + 1] - 240) + Math.abs(ref[b + 2] - 245) > 6) ++fg;
    }
  }
  const names = Object.keys(mesh.morphTargetDictionary).length;
  out.textContent = `MAD ${(sum / (W * H * 3)).toFixed(3)} targets ${names} foreground ${fg} meshes ${meshes.length}`;
} catch (e) {
  out.textContent = `ERROR ${e}`;
}
