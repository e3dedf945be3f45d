// Line plots on a plain 2D canvas. The curves are drawn once per data
// change into an offscreen canvas; moving the time cursor only copies that
// image and draws one line.

const PAD = { left: 52, right: 10, top: 20, bottom: 18 };
const BACKGROUND = '#181b20';

export const formatNumber = (v) => {
  if (Number.isInteger(v) && Math.abs(v) < 1e6) return String(v);
  return Math.abs(v) >= 1e4 || Math.abs(v) < 1e-2 ? v.toExponential(2) : v.toPrecision(3);
};

export class Plot {
  // series: [{name, color}] drawn against a shared y axis; the x axis is
  // labelled `${xName} = first${xUnit}` ... `last${xUnit}` (time by default).
  constructor(canvas, title, series, { xName = 't', xUnit = ' s' } = {}) {
    this.canvas = canvas;
    this.xName = xName;
    this.xUnit = xUnit;
    this.title = title;
    this.series = series;
    this.base = document.createElement('canvas');
    this.x = null;
    this.ys = [];
    this.cursor = null;
    new ResizeObserver(() => this.resize()).observe(canvas);
  }

  resize() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(this.canvas.clientWidth * dpr)), h = Math.max(1, Math.round(this.canvas.clientHeight * dpr));
    if (w === this.canvas.width && h === this.canvas.height) return;
    this.canvas.width = this.base.width = w;
    this.canvas.height = this.base.height = h;
    this.drawBase();
  }

  setData(x, ys) {
    this.x = x;
    this.ys = ys;
    this.drawBase();
  }

  setCursor(x) {
    this.cursor = x;
    this.drawCursor();
  }

  // Axes, labels and curves, in canvas pixels scaled by the device ratio.
  drawBase() {
    const ctx = this.base.getContext('2d'), dpr = window.devicePixelRatio || 1;
    const w = this.base.width / dpr, h = this.base.height / dpr;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = BACKGROUND;
    ctx.fillRect(0, 0, w, h);
    ctx.font = '11px system-ui, sans-serif';
    ctx.textBaseline = 'middle';
    let tx = 6;
    ctx.fillStyle = '#d8dde3';
    ctx.fillText(this.title, tx, 10);
    tx += ctx.measureText(this.title).width + 10;
    for (const s of this.series) {
      ctx.fillStyle = s.color;
      ctx.fillText(s.name, tx, 10);
      tx += ctx.measureText(s.name).width + 8;
    }
    const x = this.x, n = x ? x.length : 0;
    if (n === 0) {
      ctx.fillStyle = '#7c8590';
      ctx.fillText('no data yet', PAD.left, h / 2);
      this.drawCursor();
      return;
    }
    let lo = Infinity, hi = -Infinity;
    for (const y of this.ys) for (let i = 0; i < n; i++) if (Number.isFinite(y[i])) { lo = Math.min(lo, y[i]); hi = Math.max(hi, y[i]); }
    if (!(lo <= hi)) lo = hi = 0;
    if (lo > 0 ? lo < 0.5 * hi : -lo < 1e-9 * hi) lo = 0; // show zero when it is near (or rounding off it)
    if (hi === lo) { hi += Math.abs(hi) * 0.5 || 1; lo -= Math.abs(lo) * 0.5; }
    this.xRange = [x[0], x[n - 1] > x[0] ? x[n - 1] : x[0] + 1];
    const px = (v) => PAD.left + ((v - this.xRange[0]) / (this.xRange[1] - this.xRange[0])) * (w - PAD.left - PAD.right);
    const py = (v) => h - PAD.bottom - ((v - lo) / (hi - lo)) * (h - PAD.top - PAD.bottom);
    ctx.strokeStyle = '#3a414b';
    ctx.lineWidth = 1;
    ctx.strokeRect(PAD.left, PAD.top, w - PAD.left - PAD.right, h - PAD.top - PAD.bottom);
    ctx.fillStyle = '#9aa3ad';
    ctx.textAlign = 'right';
    ctx.fillText(formatNumber(hi), PAD.left - 4, PAD.top + 4);
    ctx.fillText(formatNumber(lo), PAD.left - 4, h - PAD.bottom - 4);
    ctx.textAlign = 'left';
    ctx.fillText(`${this.xName} = ${formatNumber(this.xRange[0])}${this.xUnit}`, PAD.left, h - PAD.bottom / 2 + 1);
    ctx.textAlign = 'right';
    ctx.fillText(`${formatNumber(this.xRange[1])}${this.xUnit}`, w - PAD.right, h - PAD.bottom / 2 + 1);
    ctx.textAlign = 'left';
    ctx.lineWidth = 1.5;
    this.series.forEach((s, k) => {
      const y = this.ys[k];
      ctx.strokeStyle = s.color;
      ctx.beginPath();
      for (let i = 0; i < n; i++) (i === 0 ? ctx.moveTo : ctx.lineTo).call(ctx, px(x[i]), py(y[i]));
      ctx.stroke();
    });
    this.px = px;
    this.drawCursor();
  }

  drawCursor() {
    const ctx = this.canvas.getContext('2d');
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.drawImage(this.base, 0, 0);
    if (this.cursor === null || !this.x || this.x.length === 0) return;
    const dpr = window.devicePixelRatio || 1;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    const cx = this.px(Math.min(Math.max(this.cursor, this.xRange[0]), this.xRange[1]));
    ctx.strokeStyle = '#f0f3f6';
    ctx.lineWidth = 1;
    ctx.beginPath();
    ctx.moveTo(cx, PAD.top);
    ctx.lineTo(cx, this.canvas.height / dpr - PAD.bottom);
    ctx.stroke();
  }
}
