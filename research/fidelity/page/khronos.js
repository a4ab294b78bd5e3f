// Renders one glTF file with the Khronos glTF Sample Renderer (npm
// @khronosgroup/gltf-viewer) in the set-up of research/fidelity/scene.py.
// render_refs.py opens this page and calls window.renderReference(setup).
//
// The renderer is made for the glTF Sample Viewer's front end, which supplies
// what a bare page has to supply here: an environment (without one the first
// frame throws on an undefined diffuseEnvMap), the look-up textures, a camera
// pose, and the libraries it reads as globals (khronos.html).

// The renderer's module with its IBL filtering sized for SwiftShader (render_refs.py).
import { GltfView, GltfState } from '/khronos/gltf-viewer.module.js';
import { createCanvas, CONTEXT_ATTRIBUTES, readBack } from './common.js';

const LIBS = '/pkg/@khronosgroup/gltf-viewer/dist/libs/';

// A uniform Radiance RGBE panorama of radiance 1.0 in every texel: (128, 128,
// 128, 129) decodes to 128 * 2^(129 - 136) = 1 exactly. The set-up's radiance is
// applied with iblIntensity instead, which keeps it exact (0.3 has no exact RGBE).
// The renderer filters any panorama into 256-pixel cube maps, so a small one
// costs no quality; a uniform environment is the same in every direction,
// so its orientation (environmentRotation) does not matter either.
function uniformPanorama(width, height) {
  const header = new TextEncoder().encode(
    `#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${height} +X ${width}\n`);
  const bytes = new Uint8Array(header.length + width * height * 4);
  bytes.set(header);
  for (let i = header.length; i < bytes.length; i += 4) {
    bytes.set([128, 128, 128, 129], i);
  }
  return bytes.buffer;
}

// The sheen albedo-scaling table (lut_sheen_E) ships with the viewer's front end,
// not with the renderer; only sheen materials read it. A 1x1 white PNG stands in.
const WHITE_PIXEL_PNG = 'data:image/png;base64,' +
  'iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAAC0lEQVR42mP4DwQACfsD/Wj6HMwAAAAASUVORK5CYII=';

// Camera-to-world matrix (column-major) of a camera at eye looking at target.
// UserCamera.lookAt would store gl-matrix's lookAt, which is the inverse (a view
// matrix), where the renderer expects the camera's own transform.
function cameraTransform(eye, target, up) {
  const sub = (a, b) => a.map((v, i) => v - b[i]);
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const unit = (a) => { const l = Math.hypot(...a); return a.map((v) => v / l); };
  const back = unit(sub(eye, target));       // the camera looks down its -z
  const right = unit(cross(up, back));
  const trueUp = cross(back, right);
  return new Float32Array([...right, 0, ...trueUp, 0, ...back, 0, ...eye, 1]);
}

window.renderReference = async (setup) => {
  const [width, height] = setup.size;
  const canvas = createCanvas(width, height);
  const gl = canvas.getContext('webgl2', CONTEXT_ATTRIBUTES);
  if (!gl) throw new Error('no WebGL2 context');

  const view = new GltfView(gl);
  const loader = view.createResourceLoader(undefined, undefined, LIBS);
  await loader.initDracoLib();  // createResourceLoader starts it without waiting
  const state = view.createState();
  state.gltf = await loader.loadGltf(setup.model);
  state.sceneIndex = state.gltf.scene ?? 0;
  state.environment = await loader.loadEnvironment(
    uniformPanorama(64, 32), { lut_sheen_E_file: WHITE_PIXEL_PNG });

  const params = state.renderingParameters;
  params.useIBL = true;
  params.iblIntensity = setup.environment.radiance;
  params.usePunctual = true;
  params.renderEnvironmentMap = false;      // transparent background
  params.clearColor = [0, 0, 0, 0];
  params.toneMap = GltfState.ToneMaps.NONE; // linear, clamped; then pow(c, 1/2.2)
  params.exposure = 1.0;

  // The renderer adds its own key and fill lights only with IBL off; the set-up's
  // directional light is given where the file has no lights of its own. drawScene
  // asks getVisibleLights for the lights every frame, so that is where it goes.
  const renderer = view.renderer;
  const scene = state.gltf.scenes[state.sceneIndex];
  const fileLights = renderer.getVisibleLights(state.gltf, scene.nodes).length;
  if (fileLights === 0) {
    const light = new renderer.lightKey.constructor();  // a gltfLight (not exported): directional
    light.intensity = setup.light.intensity;
    light.color = setup.light.color;
    // The direction light travels, as a Float32Array (the uniform upload needs one).
    light.direction = new Float32Array(setup.light.to_light.map((v) => -v));
    renderer.getVisibleLights = () => [[null, light]];
  }

  state.cameraIndex = undefined;  // the user camera, posed here
  const camera = state.userCamera;
  camera.transform = cameraTransform(setup.camera.eye, setup.camera.target, setup.camera.up);
  camera.perspective.yfov = setup.camera.yfov_deg * Math.PI / 180;
  camera.perspective.znear = setup.camera.znear;
  camera.perspective.zfar = setup.camera.zfar;

  // Every animation, at the set-up's time: a paused timer reports pausedTime.
  state.animationIndices = (state.gltf.animations ?? []).map((_, i) => i);
  state.animationTimer.pausedTime = setup.time * 1000;

  view.renderFrame(state, width, height);
  return { image: readBack(canvas, gl), file_lights: fileLights };
};
