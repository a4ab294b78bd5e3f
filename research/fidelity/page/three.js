// Renders one glTF file with three.js (npm three) in the set-up of
// research/fidelity/scene.py. render_refs.py opens this page and calls
// window.renderReference(setup).
//
// three.js lights are physical (since r155): a DirectionalLight's intensity is
// the irradiance it gives a surface facing it, and the Lambert lobe is
// albedo / pi, as in the Khronos renderer; so the two take the same numbers.

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { DRACOLoader } from 'three/addons/loaders/DRACOLoader.js';
import { createCanvas, CONTEXT_ATTRIBUTES, readBack } from './common.js';

// A uniform environment: an equirectangular float texture of radiance 1.0,
// prefiltered by PMREM like any environment map, and scaled by
// scene.environmentIntensity (the Khronos page scales by iblIntensity alike).
function uniformEnvironment(renderer) {
  const [width, height] = [64, 32];
  const texture = new THREE.DataTexture(new Float32Array(width * height * 4).fill(1.0),
                                        width, height, THREE.RGBAFormat, THREE.FloatType);
  texture.mapping = THREE.EquirectangularReflectionMapping;
  texture.colorSpace = THREE.LinearSRGBColorSpace;
  texture.needsUpdate = true;
  const pmrem = new THREE.PMREMGenerator(renderer);
  const target = pmrem.fromEquirectangular(texture);
  pmrem.dispose();
  texture.dispose();
  return target.texture;
}

window.renderReference = async (setup) => {
  const [width, height] = setup.size;
  const canvas = createCanvas(width, height);
  const gl = canvas.getContext('webgl2', CONTEXT_ATTRIBUTES);
  if (!gl) throw new Error('no WebGL2 context');
  const renderer = new THREE.WebGLRenderer({ canvas, context: gl });
  renderer.setPixelRatio(1);
  renderer.setSize(width, height, false);
  renderer.setClearColor(0x000000, 0);           // transparent background
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.outputColorSpace = THREE.SRGBColorSpace;

  const draco = new DRACOLoader().setDecoderPath('/pkg/three/examples/jsm/libs/draco/gltf/');
  const gltf = await new GLTFLoader().setDRACOLoader(draco).loadAsync(setup.model);
  draco.dispose();
  const scene = new THREE.Scene();  // gltf.scene is a Group, which has no environment
  scene.add(gltf.scene);

  scene.environment = uniformEnvironment(renderer);
  scene.environmentIntensity = setup.environment.radiance;

  // The set-up's directional light where the file has none of its own.
  let fileLights = 0;
  scene.traverse((object) => { if (object.isLight) fileLights += 1; });
  if (fileLights === 0) {
    const light = new THREE.DirectionalLight(new THREE.Color(...setup.light.color),
                                             setup.light.intensity);
    light.position.set(...setup.light.to_light);  // shines from here towards its target, the origin
    scene.add(light);
  }

  const { eye, target, up, yfov_deg, znear, zfar } = setup.camera;
  const camera = new THREE.PerspectiveCamera(yfov_deg, width / height, znear, zfar);
  camera.position.set(...eye);
  camera.up.set(...up);
  camera.lookAt(...target);

  // Every animation, at the set-up's time.
  if (gltf.animations.length > 0) {
    const mixer = new THREE.AnimationMixer(scene);
    for (const clip of gltf.animations) mixer.clipAction(clip).play();
    mixer.setTime(setup.time);
  }

  renderer.render(scene, camera);
  return { image: readBack(canvas, gl), file_lights: fileLights };
};
