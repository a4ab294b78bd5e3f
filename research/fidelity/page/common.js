// What both reference pages share: the canvas, and reading it back.
//
// The context is WebGL2 with 4x multisampling (antialias: true; SwiftShader's
// MAX_SAMPLES is 4), an alpha channel cleared to 0 so that coverage can be read
// from the image, and preserveDrawingBuffer so the frame is still there when
// toDataURL reads it. premultipliedAlpha stays true (the default): the
// multisample resolve then averages premultiplied colour, which is right at
// partly covered edge pixels, and toDataURL un-premultiplies for the PNG.

export function createCanvas(width, height) {
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  document.body.appendChild(canvas);
  return canvas;
}

export const CONTEXT_ATTRIBUTES = {
  antialias: true,
  alpha: true,
  premultipliedAlpha: true,
  preserveDrawingBuffer: true,
  powerPreference: 'high-performance',
};

// The frame as a PNG data: URL, once the GPU (here: SwiftShader) is done with it.
export function readBack(canvas, gl) {
  gl.finish();
  return canvas.toDataURL('image/png');
}
