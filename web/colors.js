// Colour maps. Instance colours go to WebGL in linear space (three.js
// converts to sRGB on output), so the tables hold linear values; legends
// drawn on a 2D canvas use the sRGB stops as they are.

const srgbToLinear = (c) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);

// A 256-entry linear RGB table interpolated between sRGB hex stops.
function colorMap(stops) {
  const rgb = stops.map((h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16) / 255));
  const table = new Float32Array(256 * 3);
  for (let i = 0; i < 256; i++) {
    const x = (i / 255) * (stops.length - 1), k = Math.min(Math.floor(x), stops.length - 2), f = x - k;
    for (let c = 0; c < 3; c++) table[3 * i + c] = srgbToLinear(rgb[k][c] * (1 - f) + rgb[k + 1][c] * f);
  }
  return { stops, table };
}

// Viridis without its darkest eighth, which vanishes on the dark background.
export const VIRIDIS = colorMap(['#482878', '#3e4989', '#31688e', '#26828e', '#1f9e89', '#35b779', '#6ece58', '#fde725']);
// Force chains: dim red for weak contacts to pale yellow for the strongest (upper part of inferno).
export const CHAINS = colorMap(['#781c6d', '#a52c60', '#cf4446', '#ed6925', '#fb9b06', '#f7d13d', '#fcffa4']);

// Writes the colour of t in [0, 1] (clamped) at out[o..o+2].
export function sample(map, t, out, o) {
  const i = 3 * Math.round(255 * (t < 0 ? 0 : t > 1 ? 1 : t));
  out[o] = map.table[i];
  out[o + 1] = map.table[i + 1];
  out[o + 2] = map.table[i + 2];
}

// Distinct colours for categories (templates): hues a golden angle apart.
export function categoryCss(k) {
  return `hsl(${(k * 137.508) % 360}, 65%, 58%)`;
}

export function category(k, out, o) {
  const h = ((k * 137.508) % 360) / 360, s = 0.65, l = 0.58;
  const q = l + s - l * s, p = 2 * l - q;
  const hue = (t) => {
    t = (t + 1) % 1;
    if (t < 1 / 6) return p + (q - p) * 6 * t;
    if (t < 1 / 2) return q;
    if (t < 2 / 3) return p + (q - p) * (2 / 3 - t) * 6;
    return p;
  };
  out[o] = srgbToLinear(hue(h + 1 / 3));
  out[o + 1] = srgbToLinear(hue(h));
  out[o + 2] = srgbToLinear(hue(h - 1 / 3));
}

// Paints a horizontal colour bar: a map's gradient, or `categories` swatches.
export function paintBar(canvas, map, categories = 0) {
  const ctx = canvas.getContext('2d'), w = canvas.width, h = canvas.height;
  if (categories > 0) {
    for (let k = 0; k < categories; k++) {
      ctx.fillStyle = categoryCss(k);
      ctx.fillRect(Math.floor((k * w) / categories), 0, Math.ceil(w / categories), h);
    }
    return;
  }
  const gradient = ctx.createLinearGradient(0, 0, w, 0);
  map.stops.forEach((s, i) => gradient.addColorStop(i / (map.stops.length - 1), s));
  ctx.fillStyle = gradient;
  ctx.fillRect(0, 0, w, h);
}
