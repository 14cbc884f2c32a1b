// Small offline time-series plots on a canvas: the last `span` seconds of a few series
// read from a store of columns ({t: [...], speed: [...], ...}, oldest first).
"use strict";

class TimePlot {
  // series: [{label, colour, key, scale}]: store[key] times scale, against store.t.
  constructor(canvas, title, unit, series, span = 60) {
    this.canvas = canvas;
    this.title = title;
    this.unit = unit;
    this.series = series;
    this.span = span;
  }

  draw(store) {
    const c = this.canvas;
    const ratio = window.devicePixelRatio || 1;
    const w = c.clientWidth, h = c.clientHeight;
    if (c.width !== Math.round(w * ratio)) { c.width = Math.round(w * ratio); c.height = Math.round(h * ratio); }
    const g = c.getContext("2d");
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, w, h);
    g.fillStyle = "#1d2125";
    g.fillRect(0, 0, w, h);
    const times = store ? store.t : [];
    const values = this.series.map((s) => (store ? store[s.key].map((v) => v * (s.scale || 1)) : []));
    g.font = "11px system-ui, sans-serif";
    if (!times.length) {
      g.fillStyle = "#e4e7eb";
      g.fillText(`${this.title} (${this.unit})`, 36, 10);
      g.fillStyle = "#9aa4af";
      g.fillText("waiting for data…", 36, h / 2 + 8);
      return;
    }
    const all = values.flat().filter(Number.isFinite);
    let lo = Math.min(0, ...all), hi = Math.max(0, ...all);
    if (hi - lo < 1e-6) { hi = lo + 1; }
    const pad = (hi - lo) * 0.1; lo -= pad; hi += pad;
    const tEnd = times[times.length - 1];
    const x = (t) => 34 + ((t - (tEnd - this.span)) / this.span) * (w - 38);
    const y = (v) => 14 + (1 - (v - lo) / (hi - lo)) * (h - 20);
    g.strokeStyle = "#363d45"; g.lineWidth = 1;
    g.beginPath(); g.moveTo(34, y(0)); g.lineTo(w - 4, y(0)); g.stroke();
    g.fillStyle = "#9aa4af"; g.font = "10px system-ui, sans-serif";
    g.fillText(hi.toFixed(hi - lo < 3 ? 2 : 0), 2, 18);
    g.fillText(lo.toFixed(hi - lo < 3 ? 2 : 0), 2, h - 6);
    this.series.forEach((s, i) => {
      const v = values[i];
      g.strokeStyle = s.colour; g.lineWidth = 1.5; g.beginPath();
      times.forEach((t, k) => (k ? g.lineTo(x(t), y(v[k])) : g.moveTo(x(t), y(v[k]))));
      g.stroke();
    });
    g.fillStyle = "#e4e7eb"; g.font = "11px system-ui, sans-serif";
    const now = this.series.map((s, i) => `${s.label} ${values[i][values[i].length - 1].toFixed(1)}`);
    g.fillText(`${this.title} (${this.unit})  ${now.join("  ").trim()}`, 36, 10);
  }
}

window.TimePlot = TimePlot;
