// Small offline time-series plots on a canvas: the last `span` seconds of a few series.
"use strict";

class TimePlot {
  // series: [{label, colour}], span: seconds kept and shown.
  constructor(canvas, title, unit, series, span = 60) {
    this.canvas = canvas;
    this.title = title;
    this.unit = unit;
    this.series = series;
    this.span = span;
    this.times = [];
    this.values = series.map(() => []);
  }

  push(t, values) {
    const last = this.times.length ? this.times[this.times.length - 1] : -Infinity;
    if (t < last) this.clear(); // time went back: a new scenario or a replay seek
    this.times.push(t);
    values.forEach((v, i) => this.values[i].push(v));
    let drop = 0;
    while (drop < this.times.length && this.times[drop] < t - this.span) drop++;
    if (drop) {
      this.times.splice(0, drop);
      this.values.forEach((v) => v.splice(0, drop));
    }
  }

  clear() {
    this.times = [];
    this.values = this.series.map(() => []);
  }

  draw() {
    const c = this.canvas;
    const ratio = window.devicePixelRatio || 1;
    const w = c.clientWidth, h = c.clientHeight;
    if (c.width !== Math.round(w * ratio)) { c.width = Math.round(w * ratio); c.height = Math.round(h * ratio); }
    const g = c.getContext("2d");
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, w, h);
    g.fillStyle = "#1d2125";
    g.fillRect(0, 0, w, h);
    const all = this.values.flat().filter(Number.isFinite);
    let lo = Math.min(0, ...all), hi = Math.max(0, ...all);
    if (hi - lo < 1e-6) { hi = lo + 1; }
    const pad = (hi - lo) * 0.1; lo -= pad; hi += pad;
    const tEnd = this.times.length ? this.times[this.times.length - 1] : 0;
    const x = (t) => 34 + ((t - (tEnd - this.span)) / this.span) * (w - 38);
    const y = (v) => 14 + (1 - (v - lo) / (hi - lo)) * (h - 20);
    g.strokeStyle = "#363d45"; g.lineWidth = 1;
    g.beginPath(); g.moveTo(34, y(0)); g.lineTo(w - 4, y(0)); g.stroke();
    g.fillStyle = "#9aa4af"; g.font = "10px system-ui, sans-serif";
    g.fillText(hi.toFixed(hi - lo < 3 ? 2 : 0), 2, 18);
    g.fillText(lo.toFixed(hi - lo < 3 ? 2 : 0), 2, h - 6);
    this.series.forEach((s, i) => {
      const v = this.values[i];
      g.strokeStyle = s.colour; g.lineWidth = 1.5; g.beginPath();
      this.times.forEach((t, k) => (k ? g.lineTo(x(t), y(v[k])) : g.moveTo(x(t), y(v[k]))));
      g.stroke();
    });
    g.fillStyle = "#e4e7eb"; g.font = "11px system-ui, sans-serif";
    const now = this.series.map((s, i) => {
      const v = this.values[i];
      return v.length ? `${s.label} ${v[v.length - 1].toFixed(1)}` : s.label;
    });
    g.fillText(`${this.title} (${this.unit})  ${now.join("  ")}`, 36, 10);
  }
}

window.TimePlot = TimePlot;
