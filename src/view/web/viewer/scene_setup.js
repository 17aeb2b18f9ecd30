// The 3D view: renderer, camera and lights (world frame z-up, as in the scenes), the camera
// framing both bodies, the orbit controls, and the view's size.
import { THREE } from './three_global.js';

// Renderer, scene and camera (a light rides on it) in CONTAINER.
export function createView(container) {
  const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(0x1d2024);
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, window.innerWidth / window.innerHeight, 1e-4, 100);
  camera.up.set(0, 0, 1);
  scene.add(camera);
  scene.add(new THREE.AmbientLight(0xffffff, 0.5));
  const light = new THREE.DirectionalLight(0xffffff, 0.7);
  light.position.set(0.3, 0.5, 1);
  camera.add(light);
  return {container: container, renderer: renderer, scene: scene, camera: camera};
}

// Points VIEW's camera at the bounding sphere of BODIES' meshes at their poses, and returns it.
export function frameBodies(view, bodies) {
  view.scene.updateMatrixWorld(true);  // the bodies' poses, before the first render computes them
  const box = new THREE.Box3();
  bodies.forEach(function (b) { box.expandByObject(b.mesh); });
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const r = Math.max(sphere.radius, 1e-3);
  const dir = new THREE.Vector3(1.0, -1.6, 0.9).normalize();
  const camera = view.camera;
  camera.position.copy(sphere.center).addScaledVector(dir, 2.7 * r);
  camera.near = r * 0.01;
  camera.far = r * 50;
  camera.updateProjectionMatrix();
  return sphere;
}

// Orbit controls of VIEW's camera about TARGET.
export function addOrbitControls(view, target) {
  const controls = new THREE.OrbitControls(view.camera, view.renderer.domElement);
  controls.target.copy(target);
  controls.update();
  return controls;
}

// The 3D view fills the window above BAR (the replay / live bar) when it is shown.
export function layoutView(view, bar) {
  const container = view.container;
  container.style.bottom = bar.hidden ? '0px' : bar.offsetHeight + 'px';
  const w = Math.max(1, container.clientWidth), h = Math.max(1, container.clientHeight);
  view.camera.aspect = w / h;
  view.camera.updateProjectionMatrix();
  view.renderer.setSize(w, h);
}
