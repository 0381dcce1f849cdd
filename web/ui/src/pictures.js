// Pictures the in-browser engine does not make (it has no cairo and no cgif): a PNG of its SVG
// drawn on a canvas, and a GIF of its scene posed at each sample, drawn the same way and encoded
// here by gifenc. The geometry is the engine's; the browser only rasterises it.
import { GIFEncoder, quantize, applyPalette } from 'gifenc';
import { drawingSvg, poseDrawing } from './drawing.js';

// An <img> of SVG text, decoded.
async function svgImage(svgText) {
  const url = URL.createObjectURL(new Blob([svgText], { type: 'image/svg+xml' }));
  try {
    const img = new Image();
    img.src = url;
    await img.decode();
    return img;
  } finally {
    URL.revokeObjectURL(url);
  }
}

function whiteCanvas(width, height) {
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const ctx = canvas.getContext('2d', { willReadFrequently: true });
  ctx.fillStyle = '#fff';
  ctx.fillRect(0, 0, width, height);
  return { canvas, ctx };
}

// The engine's SVG drawing (`nbar draw`), as a PNG of its own size.
export async function pngFromSvg(svgText) {
  const img = await svgImage(svgText);
  const { canvas, ctx } = whiteCanvas(img.naturalWidth || 900, img.naturalHeight || 640);
  ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
  return new Promise((resolve, reject) => canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('no PNG'))), 'image/png'));
}

// The scene (`format: "scene"`) posed at every sample, one GIF frame each, at 4 s a cycle as
// the app's animation plays; one palette for all frames (a drawing has few colours).
export async function gifFromScene(scene, seconds = 4) {
  const holder = document.createElement('div');
  holder.innerHTML = drawingSvg(scene);
  const svg = holder.firstElementChild;
  svg.setAttribute('width', scene.width);
  svg.setAttribute('height', scene.height);
  const { ctx } = whiteCanvas(scene.width, scene.height);
  const frames = [];
  const steps = Math.max(scene.steps.length, 1);
  for (let k = 0; k < steps; k++) {
    poseDrawing(svg, scene, k);
    ctx.fillStyle = '#fff';
    ctx.fillRect(0, 0, scene.width, scene.height);
    ctx.drawImage(await svgImage(new XMLSerializer().serializeToString(svg)), 0, 0);
    frames.push(ctx.getImageData(0, 0, scene.width, scene.height).data);
  }
  const palette = quantize(frames[0], 256);
  const gif = GIFEncoder();
  const delay = Math.round((seconds * 1000) / steps);
  for (const data of frames) gif.writeFrame(applyPalette(data, palette), scene.width, scene.height, { palette, delay });
  gif.finish();
  return new Blob([gif.bytes()], { type: 'image/gif' });
}
