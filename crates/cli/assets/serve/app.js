// fair serve: the page. It draws what the JSON API returns and sends what the user asks for;
// every number (measures, combs, z values, highlight lines, faired points) comes from the API.
// The history (undo/redo) lives here, in this tab: the server keeps nothing between requests.
"use strict";

(function () {
  const SVG = "http://www.w3.org/2000/svg";
  const $ = (id) => document.getElementById(id);

  const state = {
    methods: [],
    defaults: {},
    history: [], // {label, type, name, points, rows, columns, report, drawing, before, beforePoints}
    index: -1,
    bad: [],
    fixed: [],
    view: { k: 1, px: 0, py: 0 },
    combBase: null, // |curvature| that maps to the full tooth length, fixed per document
    busy: false,
  };

  // ---------------------------------------------------------------- requests

  async function api(path, body) {
    const options = body === undefined ? {} : {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body),
    };
    const response = await fetch(path, options);
    let value;
    try {
      value = await response.json();
    } catch (e) {
      throw new Error(`${path}: answer is not JSON (status ${response.status})`);
    }
    if (!response.ok) {
      throw new Error(value && value.error ? value.error : `${path}: status ${response.status}`);
    }
    return value;
  }

  function setStatus(text, kind) {
    const status = $("status");
    status.textContent = text;
    status.className = kind || "";
  }

  async function busy(label, work) {
    if (state.busy) return;
    state.busy = true;
    document.body.dataset.state = "busy";
    setStatus(label + "…", "busy");
    updateButtons();
    try {
      await work();
      document.body.dataset.state = "ready";
      setStatus("ready", "");
    } catch (error) {
      document.body.dataset.state = "error";
      setStatus(error.message, "error");
    } finally {
      state.busy = false;
      updateButtons();
    }
  }

  // ---------------------------------------------------------------- history

  const current = () => state.history[state.index] || null;

  function pushEntry(entry) {
    state.history.splice(state.index + 1);
    state.history.push(entry);
    state.index = state.history.length - 1;
    state.bad = [];
    render();
  }

  function loadDocument(value, label) {
    state.history = [];
    state.index = -1;
    state.bad = [];
    state.fixed = [];
    state.view = { k: 1, px: 0, py: 0 };
    state.combBase = combBase(value.drawing);
    pushEntry({
      label,
      type: value.type,
      name: value.name,
      points: value.points,
      rows: value.rows,
      columns: value.columns,
      report: value.report,
      drawing: value.drawing,
      before: null,
      beforePoints: null,
    });
    fillMethods();
  }

  function go(index) {
    if (index < 0 || index >= state.history.length || state.busy) return;
    state.index = index;
    state.bad = [];
    render();
  }

  // ---------------------------------------------------------------- actions

  async function loadDataset(name) {
    if (!name) return;
    await busy(`loading ${name}`, async () => {
      const value = await api(`/api/datasets/${name.split("/").map(encodeURIComponent).join("/")}`);
      loadDocument(value, `loaded ${value.name}`);
    });
  }

  async function upload(file) {
    await busy(`reading ${file.name}`, async () => {
      const text = await file.text();
      const value = await api("/api/inspect", { name: file.name, text });
      loadDocument(value, `opened ${value.name}`);
    });
  }

  function selectedMethod() {
    return state.methods.find((m) => m.name === $("method").value) || null;
  }

  function constraints(withPoints) {
    const c = {};
    if (state.fixed.length) c.fixed = state.fixed.slice();
    if (withPoints && state.bad.length) c.points = state.bad.slice();
    const tolerance = $("tolerance").value.trim();
    if (tolerance !== "") c.tolerance = Number(tolerance);
    const clamp = $("clamp-ends").value;
    if (clamp) c["clamp-ends"] = clamp;
    const corners = cornersOf($("corners").value);
    if (corners !== null) c.corners = corners;
    return c;
  }

  // The corners field as `constraints.corners` (`--corners`): empty is the default (not
  // sent), `auto` or `none` as written, else point indices separated by commas or spaces
  // (anything else is sent as it reads, for the server to refuse with its message).
  function cornersOf(text) {
    const t = text.trim().toLowerCase();
    if (t === "") return null;
    if (t === "auto" || t === "none") return t;
    return t.split(/[\s,]+/).filter((s) => s !== "").map((s) => (/^\d+$/.test(s) ? Number(s) : s));
  }

  async function fair(method, params, withPoints, label) {
    const entry = current();
    if (!entry) return;
    await busy(label, async () => {
      const body = {
        name: entry.name,
        points: entry.points,
        method: method.name,
        params,
        constraints: constraints(withPoints),
      };
      let value;
      if (entry.type === "surface") {
        delete body.constraints.corners; // a curve's constraint
        body.rows = entry.rows;
        body.columns = entry.columns;
        value = await api("/api/surface", body);
      } else {
        body.kind = $("kind").value;
        value = await api("/api/curve", body);
      }
      pushEntry({
        label,
        type: entry.type,
        name: entry.name,
        points: value.points,
        rows: value.rows,
        columns: value.columns,
        report: value.report,
        drawing: value.drawing.after,
        before: value.drawing.before,
        beforePoints: entry.points,
        request: body,
      });
    });
  }

  function fairSelected() {
    const entry = current();
    if (!entry || !state.bad.length) return;
    let method = selectedMethod();
    let params = formParams();
    if (!method || !method.takes_points) {
      const fallback = entry.type === "surface" ? "zhang-cheng" : "strain-energy";
      method = state.methods.find((m) => m.name === fallback && m.kind === kindOf(entry));
      params = {};
    }
    if (!method) return;
    fair(method, params, true, `${method.name} on ${state.bad.join(", ")}`);
  }

  function runMethod() {
    const method = selectedMethod();
    if (method) fair(method, formParams(), false, method.name);
  }

  function togglePoint(index) {
    if (!current() || state.busy) return;
    const mode = document.querySelector('input[name="mode"]:checked').value;
    const [mine, other] = mode === "fixed" ? [state.fixed, state.bad] : [state.bad, state.fixed];
    const at = mine.indexOf(index);
    if (at >= 0) {
      mine.splice(at, 1);
    } else {
      const there = other.indexOf(index);
      if (there >= 0) other.splice(there, 1);
      mine.push(index);
    }
    state.fixed.sort((a, b) => a - b);
    render();
  }

  // ---------------------------------------------------------------- downloads

  function download(name, text, type) {
    const url = URL.createObjectURL(new Blob([text], { type }));
    const a = document.createElement("a");
    a.href = url;
    a.download = name;
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  }

  const stem = (entry) => entry.name.replace(/^.*\//, "").replace(/\.[^.]*$/, "");

  function downloadPoints() {
    const entry = current();
    if (!entry) return;
    // String(x) is the shortest decimal that reads back as the same double: nothing is lost.
    let text;
    if (entry.type === "surface") {
      text = "i,j,x,y,z\n" + entry.points.map((p, k) =>
        [Math.floor(k / entry.columns), k % entry.columns, ...p].map(String).join(",")).join("\n") + "\n";
    } else {
      const header = entry.points[0].length === 3 ? "x,y,z" : "x,y";
      text = header + "\n" + entry.points.map((p) => p.map(String).join(",")).join("\n") + "\n";
    }
    download(`${stem(entry)}-${state.index}.csv`, text, "text/csv");
  }

  // The CAD file of the current result: the request of the step that made it, sent again to
  // /api/cad (the server keeps no state), so that the file holds that method's own curve; a
  // loaded document is written as it is ("fair": false).
  async function downloadCad() {
    const entry = current();
    if (!entry) return;
    const format = $("cad-format").value;
    await busy(`writing ${format.toUpperCase()}`, async () => {
      let body;
      if (entry.request) {
        body = Object.assign({}, entry.request, { format });
      } else {
        body = { name: entry.name, points: entry.points, format, fair: false };
        if (entry.type === "surface") {
          body.rows = entry.rows;
          body.columns = entry.columns;
        } else {
          body.kind = $("kind").value;
        }
      }
      const response = await fetch("/api/cad", {
        method: "POST",
        headers: { "Content-Type": "application/json" },
        body: JSON.stringify(body),
      });
      if (!response.ok) {
        let message = `/api/cad: status ${response.status}`;
        try {
          const value = await response.json();
          if (value && value.error) message = value.error;
        } catch (e) { /* not JSON: keep the status */ }
        throw new Error(message);
      }
      const blob = await response.blob();
      const match = /filename="([^"]+)"/.exec(response.headers.get("Content-Disposition") || "");
      download(match ? match[1] : `${stem(entry)}-${state.index}.${format}`, blob, blob.type);
    });
  }

  function downloadReport() {
    const entry = current();
    if (entry) download(`${stem(entry)}-${state.index}.json`, JSON.stringify(entry.report, null, 2) + "\n", "application/json");
  }

  // ---------------------------------------------------------------- methods and forms

  const kindOf = (entry) => (entry.type === "surface" ? "surface" : "curve");

  function fillMethods() {
    const entry = current();
    const select = $("method");
    const previous = select.value;
    select.textContent = "";
    if (!entry) return;
    const spatial = entry.type === "curve" && entry.points[0] && entry.points[0].length === 3;
    const usable = state.methods.filter((m) => m.kind === kindOf(entry) && !(spatial && m.planar_only));
    for (const m of usable) {
      const option = document.createElement("option");
      option.value = m.name;
      option.textContent = m.name + (m.takes_points ? " (takes points)" : "");
      select.appendChild(option);
    }
    const fallback = entry.type === "surface" ? state.defaults.surface
      : entry.report.kind === "function" ? state.defaults.function : state.defaults.parametric;
    select.value = usable.some((m) => m.name === previous) ? previous : fallback;
    fillParams();
  }

  function resolve(schema, root) {
    let s = schema || {};
    for (let guard = 0; s.$ref && guard < 8; guard++) {
      const path = s.$ref.replace(/^#\//, "").split("/");
      let target = root;
      for (const part of path) target = target ? target[part] : undefined;
      s = Object.assign({}, target || {}, s, { $ref: undefined });
    }
    return s;
  }

  // The choices of an enum-like schema: `enum`, or `oneOf`/`anyOf` of `const`s (schemars).
  function choices(schema, root) {
    if (Array.isArray(schema.enum)) return schema.enum.map((v) => ({ value: v, about: "" }));
    const list = schema.oneOf || schema.anyOf;
    if (!Array.isArray(list)) return null;
    const out = [];
    for (const item of list.map((i) => resolve(i, root))) {
      if (item.const !== undefined) out.push({ value: item.const, about: item.description || "" });
      else if (Array.isArray(item.enum)) item.enum.forEach((v) => out.push({ value: v, about: item.description || "" }));
      else if (item.type === "null") continue;
      else return null;
    }
    return out.length ? out : null;
  }

  function fillParams() {
    const form = $("params");
    form.textContent = "";
    const method = selectedMethod();
    $("method-about").textContent = method ? `${method.summary} — ${method.paper}` : "";
    $("kind-field").hidden = !current() || current().type === "surface";
    if (!method) return;
    const schema = method.schema || {};
    const properties = schema.properties || {};
    $("params-count").textContent = String(Object.keys(properties).length);
    for (const [name, raw] of Object.entries(properties)) {
      const prop = resolve(raw, schema);
      const label = document.createElement("label");
      label.className = "param";
      label.title = prop.description || "";
      const title = document.createElement("span");
      title.className = "name";
      title.textContent = name;
      label.appendChild(title);
      const fallback = prop.default;
      const list = prop.type === "boolean" ? [{ value: true, about: "" }, { value: false, about: "" }] : choices(prop, schema);
      let input;
      if (list) {
        input = document.createElement("select");
        for (const c of list) {
          const option = document.createElement("option");
          option.value = JSON.stringify(c.value);
          option.textContent = String(c.value) + (c.value === fallback ? " (default)" : "");
          if (c.about) option.title = c.about;
          input.appendChild(option);
        }
        if (fallback !== undefined) input.value = JSON.stringify(fallback);
        input.dataset.kind = "choice";
      } else {
        input = document.createElement("input");
        input.type = "text";
        input.placeholder = fallback === undefined ? "" : String(fallback);
        input.dataset.kind = prop.type === "string" ? "string" : "number-or-text";
      }
      input.name = name;
      input.dataset.default = JSON.stringify(fallback === undefined ? null : fallback);
      label.appendChild(input);
      const about = document.createElement("span");
      about.className = "about";
      about.textContent = (prop.description || "").split("\n")[0] +
        (fallback === undefined ? "" : ` (default ${String(fallback)})`);
      label.appendChild(about);
      form.appendChild(label);
    }
  }

  // The values changed from their defaults; the rest is left to the method.
  function formParams() {
    const params = {};
    for (const input of $("params").querySelectorAll("input, select")) {
      if (input.dataset.kind === "choice") {
        if (input.value !== input.dataset.default) params[input.name] = JSON.parse(input.value);
        continue;
      }
      const text = input.value.trim();
      if (text === "") continue;
      const number = Number(text);
      params[input.name] = input.dataset.kind !== "string" && text !== "" && Number.isFinite(number) ? number : text;
    }
    return params;
  }

  // ---------------------------------------------------------------- drawing helpers

  function el(name, attributes, parent) {
    const node = document.createElementNS(SVG, name);
    for (const [key, value] of Object.entries(attributes || {})) node.setAttribute(key, value);
    if (parent) parent.appendChild(node);
    return node;
  }

  function clear(svg) {
    while (svg.firstChild) svg.removeChild(svg.firstChild);
    const width = svg.clientWidth || 600;
    const height = svg.clientHeight || 300;
    svg.setAttribute("viewBox", `0 0 ${width} ${height}`);
    return { width, height };
  }

  const finite = (p) => p && Number.isFinite(p[0]) && Number.isFinite(p[1]);

  function bounds(lists) {
    let [x0, x1, y0, y1] = [Infinity, -Infinity, Infinity, -Infinity];
    for (const list of lists) {
      for (const p of list || []) {
        if (!finite(p)) continue;
        x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]);
        y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]);
      }
    }
    if (!Number.isFinite(x0)) return [0, 1, 0, 1];
    if (x1 - x0 === 0) { x0 -= 0.5; x1 += 0.5; }
    if (y1 - y0 === 0) { y0 -= 0.5; y1 += 0.5; }
    return [x0, x1, y0, y1];
  }

  // A linear map from data to screen: fitted to `b` with a margin, equal aspect if asked,
  // then zoomed and panned by `view` (main view only).
  function fit(b, size, equal, view, margin) {
    const m = margin === undefined ? 28 : margin;
    const w = Math.max(size.width - 2 * m, 10);
    const h = Math.max(size.height - 2 * m, 10);
    let sx = w / (b[1] - b[0]);
    let sy = h / (b[3] - b[2]);
    if (equal) sx = sy = Math.min(sx, sy);
    const cx = (b[0] + b[1]) / 2;
    const cy = (b[2] + b[3]) / 2;
    const v = view || { k: 1, px: 0, py: 0 };
    const X = (x) => ((x - cx) * sx) * v.k + size.width / 2 + v.px;
    const Y = (y) => (-(y - cy) * sy) * v.k + size.height / 2 + v.py;
    return { X, Y, sx: sx * v.k, sy: sy * v.k };
  }

  function path(points, map) {
    let d = "";
    let pen = false;
    for (const p of points || []) {
      if (!finite(p)) { pen = false; continue; }
      d += (pen ? "L" : "M") + map.X(p[0]).toFixed(2) + " " + map.Y(p[1]).toFixed(2);
      pen = true;
    }
    return d;
  }

  function percentile(values, q) {
    const v = values.filter(Number.isFinite).map(Math.abs).sort((a, b) => a - b);
    if (!v.length) return 0;
    return v[Math.min(v.length - 1, Math.floor(q * (v.length - 1)))];
  }

  function combBase(drawing) {
    if (!drawing || !drawing.comb) return null;
    const p = percentile(drawing.comb.curvature, 1);
    return p > 0 ? p : null;
  }

  function formatNumber(v) {
    if (v === null || v === undefined) return "–";
    if (typeof v !== "number") return String(v);
    if (Number.isInteger(v) && Math.abs(v) < 1e9) return String(v);
    const a = Math.abs(v);
    if (a !== 0 && (a < 1e-3 || a >= 1e5)) return v.toExponential(4);
    return v.toPrecision(6).replace(/(\.\d*?)0+$/, "$1").replace(/\.$/, "");
  }

  // ---------------------------------------------------------------- main view

  function renderMain() {
    const svg = $("main-view");
    const size = clear(svg);
    const entry = current();
    if (!entry) return;
    $("comb-controls").hidden = entry.type === "surface";
    if (entry.type === "surface") return renderSurfaceMain(svg, size, entry);
    const d = entry.drawing;
    const b = bounds([d.samples, d.view, entry.before && entry.before.samples]);
    const map = fit(b, size, !d.function, state.view);
    $("main-caption").textContent = `${entry.name} — ${d.function ? "function y(x)" : "parametric curve"}` +
      (d.plane === "xz" ? ", seen in the x–z plane" : "") + `, ${entry.points.length} points`;
    $("comb-legend").textContent = "curvature comb";
    // Comb: teeth perpendicular to the curve on screen, length ∝ curvature (one scale per document).
    if (d.comb && state.combBase) {
      // The longest tooth of the document's first state is 15% of the view (× the slider);
      // teeth longer than half the view are cut there.
      const view = Math.min(size.width, size.height);
      const scale = Math.pow(2, Number($("comb-scale").value)) * 0.15 * view / state.combBase;
      const longest = 0.5 * view;
      let teeth = "";
      let envelope = "";
      let pen = false;
      const c = d.comb;
      for (let i = 0; i < c.points.length; i++) {
        const p = c.points[i], n = c.normals[i], k = c.curvature[i];
        if (!finite(p) || !finite(n) || !Number.isFinite(k)) { pen = false; continue; }
        // Screen tangent from the world tangent (n rotated), then its left normal on screen.
        const tx = n[1] * map.sx, ty = n[0] * map.sy; // screen y points down
        const length = Math.hypot(tx, ty) || 1;
        let nx = -ty / length, ny = tx / length;
        // Orient like the world normal mapped to the screen.
        if (nx * n[0] * map.sx - ny * n[1] * map.sy < 0) { nx = -nx; ny = -ny; }
        const x = map.X(p[0]), y = map.Y(p[1]);
        const tooth = Math.max(-longest, Math.min(longest, scale * k));
        const tipX = x + tooth * nx, tipY = y + tooth * ny;
        teeth += `M${x.toFixed(1)} ${y.toFixed(1)}L${tipX.toFixed(1)} ${tipY.toFixed(1)}`;
        envelope += (pen ? "L" : "M") + tipX.toFixed(1) + " " + tipY.toFixed(1);
        pen = true;
      }
      el("path", { id: "comb", class: "comb", d: teeth }, svg);
      el("path", { id: "comb-envelope", class: "comb-envelope", d: envelope }, svg);
    }
    if (entry.before) {
      el("path", { class: "curve before", d: path(entry.before.samples, map) }, svg);
      for (const p of entry.before.view) {
        if (finite(p)) el("circle", { class: "marker before", cx: map.X(p[0]), cy: map.Y(p[1]), r: 2.5 }, svg);
      }
    }
    el("path", { id: "curve", class: "curve now", d: path(d.samples, map) }, svg);
    drawPickable(svg, d.view, map);
  }

  function drawPickable(svg, view, map) {
    const group = el("g", { id: "points" }, svg);
    view.forEach((p, i) => {
      if (!finite(p)) return;
      const cls = ["point"];
      if (state.bad.includes(i)) cls.push("bad");
      if (state.fixed.includes(i)) cls.push("fixed");
      const x = map.X(p[0]), y = map.Y(p[1]);
      const node = state.fixed.includes(i)
        ? el("rect", { x: x - 4.5, y: y - 4.5, width: 9, height: 9 }, group)
        : el("circle", { cx: x, cy: y, r: state.bad.includes(i) ? 6 : 4 }, group);
      node.setAttribute("class", cls.join(" "));
      node.dataset.index = i;
      const title = el("title", {}, node);
      title.textContent = `point ${i}: ${current().points[i].map(formatNumber).join(", ")}`;
    });
  }

  function renderSurfaceMain(svg, size, entry) {
    const d = entry.drawing;
    const h = d.highlights;
    const before = entry.before && entry.before.highlights;
    let view, lines;
    if (h) {
      view = h.points;
      lines = h.lines;
      $("main-caption").textContent = `${entry.name} — highlight lines, ${entry.rows} × ${entry.columns} grid`;
      $("comb-legend").textContent = "grid lines";
    } else {
      view = d.view;
      lines = [];
      $("main-caption").textContent = `${entry.name} — grid seen from above (no highlight lines for this grid)`;
    }
    const b = bounds([view, ...(lines || [])]);
    const map = fit(b, size, true, state.view);
    // The grid's rows and columns, faint, under the lines.
    let grid = "";
    for (let i = 0; i < entry.rows; i++) {
      grid += path(view.slice(i * entry.columns, (i + 1) * entry.columns), map);
    }
    for (let j = 0; j < entry.columns; j++) {
      const column = [];
      for (let i = 0; i < entry.rows; i++) column.push(view[i * entry.columns + j]);
      grid += path(column, map);
    }
    el("path", { class: "grid", d: grid }, svg);
    if (before) el("path", { class: "highlight before", d: before.lines.map((l) => path(l, map)).join("") }, svg);
    el("path", { id: "highlights", class: "highlight now", d: lines.map((l) => path(l, map)).join("") }, svg);
    drawPickable(svg, view, map);
  }

  // ---------------------------------------------------------------- lower views

  function renderBars() {
    const svg = $("z-view");
    const size = clear(svg);
    const entry = current();
    if (!entry || entry.type === "surface") return entry && renderZMap(svg, size, entry, entry.drawing, "z-map");
    $("z-caption").textContent = "third-derivative jumps z_i (click a bar to pick its point)";
    const z = entry.drawing.z || [];
    const zb = entry.before ? entry.before.z || [] : [];
    const top = Math.max(1e-300, ...z.filter(Number.isFinite), ...zb.filter(Number.isFinite));
    const m = { l: 12, r: 10, t: 10, b: 22 };
    const w = (size.width - m.l - m.r) / Math.max(z.length, 1);
    const H = size.height - m.t - m.b;
    el("line", { class: "axis", x1: m.l, y1: m.t + H, x2: size.width - m.r, y2: m.t + H }, svg);
    el("line", { class: "axis", x1: m.l, y1: m.t, x2: m.l, y2: m.t + H }, svg);
    const label = el("text", { class: "tick", x: size.width - m.r, y: m.t + 8, "text-anchor": "end" }, svg);
    label.textContent = `max ${formatNumber(top)}`;
    const group = el("g", { id: "bars" }, svg);
    z.forEach((v, i) => {
      const x = m.l + i * w;
      if (zb.length && Number.isFinite(zb[i])) {
        el("rect", { class: "bar before", x: x + 0.1 * w, width: Math.max(0.4 * w, 0.5), y: m.t + H - H * zb[i] / top, height: H * zb[i] / top }, group);
      }
      const cls = ["bar", "now"];
      if (state.bad.includes(i)) cls.push("bad");
      if (state.fixed.includes(i)) cls.push("fixed");
      const v1 = Number.isFinite(v) ? v : 0;
      const x1 = zb.length ? x + 0.5 * w : x + 0.15 * w;
      const bar = el("rect", { class: cls.join(" "), x: x1, width: Math.max((zb.length ? 0.4 : 0.7) * w, 0.5), y: m.t + H - H * v1 / top, height: H * v1 / top }, group);
      bar.dataset.index = i;
      // A transparent full-height target, so that small bars are easy to click.
      const hit = el("rect", { class: "hit", x, width: w, y: m.t, height: H }, group);
      hit.dataset.index = i;
      el("title", {}, hit).textContent = `z_${i} = ${formatNumber(v)}` + (zb.length ? ` (before ${formatNumber(zb[i])})` : "");
    });
    const step = Math.max(1, Math.ceil(z.length / 12));
    for (let i = 0; i < z.length; i += step) {
      const t = el("text", { class: "tick", x: m.l + (i + 0.5) * w, y: size.height - 6, "text-anchor": "middle" }, svg);
      t.textContent = String(i);
    }
  }

  function renderCurvature() {
    const svg = $("curvature-view");
    const size = clear(svg);
    const entry = current();
    if (!entry) return;
    if (entry.type === "surface") {
      if (entry.before) {
        $("curvature-caption").textContent = "z_ij before this step (same colour scale)";
        renderZMap(svg, size, entry, entry.before, "z-map-before");
      } else {
        $("curvature-caption").textContent = "the grid seen from above (x, y)";
        renderTopView(svg, size, entry);
      }
      return;
    }
    const c = entry.drawing.curvature;
    if (!c) return;
    const cb = entry.before && entry.before.curvature;
    $("curvature-caption").textContent = c.title;
    const b = bounds([c.line, c.knots, cb && cb.line]);
    const map = fit(b, size, false, null, 26);
    if (b[2] < 0 && b[3] > 0) {
      el("line", { class: "axis", x1: 0, x2: size.width, y1: map.Y(0), y2: map.Y(0) }, svg);
    }
    if (cb) el("path", { class: "curve before", d: path(cb.line, map) }, svg);
    el("path", { id: "curvature-line", class: "curve now", d: path(c.line, map) }, svg);
    for (const p of c.knots) {
      if (finite(p)) el("circle", { class: "marker now", cx: map.X(p[0]), cy: map.Y(p[1]), r: 2.2 }, svg);
    }
    const ylabel = el("text", { class: "tick", x: 4, y: 12 }, svg);
    ylabel.textContent = `${c.y_label}: ${formatNumber(b[2])} … ${formatNumber(b[3])}`;
    const xlabel = el("text", { class: "tick", x: size.width - 4, y: size.height - 4, "text-anchor": "end" }, svg);
    xlabel.textContent = c.x_label;
  }

  function renderTopView(svg, size, entry) {
    const view = entry.drawing.view;
    const map = fit(bounds([view]), size, true, null, 16);
    let grid = "";
    for (let i = 0; i < entry.rows; i++) grid += path(view.slice(i * entry.columns, (i + 1) * entry.columns), map);
    for (let j = 0; j < entry.columns; j++) {
      const column = [];
      for (let i = 0; i < entry.rows; i++) column.push(view[i * entry.columns + j]);
      grid += path(column, map);
    }
    el("path", { class: "curve now", d: grid }, svg);
  }

  function colour(t) {
    // Dark blue (0) to yellow (1) through teal: readable, monotone in lightness.
    const stops = [[13, 8, 135], [84, 2, 163], [139, 10, 165], [185, 50, 137], [219, 92, 104], [244, 136, 73], [254, 188, 43], [240, 249, 33]];
    const x = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
    const i = Math.min(Math.floor(x), stops.length - 2);
    const f = x - i;
    const c = stops[i].map((v, k) => Math.round(v + f * (stops[i + 1][k] - v)));
    return `rgb(${c[0]},${c[1]},${c[2]})`;
  }

  function renderZMap(svg, size, entry, drawing, id) {
    if (id === "z-map") $("z-caption").textContent = "z_ij (click a cell to pick its point)";
    const z = drawing.z || [];
    const all = [entry.drawing, entry.before].filter(Boolean).flatMap((d) => (d.z || []).flat()).filter(Number.isFinite);
    const top = Math.max(1e-300, ...all);
    const rows = entry.rows, columns = entry.columns;
    const cell = Math.min((size.width - 20) / columns, (size.height - 20) / rows);
    const x0 = (size.width - cell * columns) / 2, y0 = (size.height - cell * rows) / 2;
    const group = el("g", { id }, svg);
    for (let i = 0; i < rows; i++) {
      for (let j = 0; j < columns; j++) {
        const k = i * columns + j;
        const v = z[i] ? z[i][j] : null;
        const cls = ["cell"];
        if (id === "z-map" && state.bad.includes(k)) cls.push("bad");
        if (id === "z-map" && state.fixed.includes(k)) cls.push("fixed");
        const rect = el("rect", { class: cls.join(" "), x: x0 + j * cell, y: y0 + i * cell, width: cell, height: cell, fill: Number.isFinite(v) ? colour(v / top) : "#ccc" }, group);
        if (id === "z-map") rect.dataset.index = k;
        el("title", {}, rect).textContent = `point ${k} (i ${i}, j ${j}): z = ${formatNumber(v)}`;
      }
    }
    const t = el("text", { class: "tick", x: 4, y: size.height - 4 }, svg);
    t.textContent = `0 … ${formatNumber(top)}`;
  }

  // ---------------------------------------------------------------- report, lists, buttons

  function renderReport() {
    const entry = current();
    const measures = $("report-measures");
    const run = $("report-run");
    measures.textContent = "";
    run.textContent = "";
    $("report-method").textContent = entry ? `(${entry.report.method})` : "";
    if (!entry) return;
    const r = entry.report;
    const row = (parent, label, cells) => {
      const tr = document.createElement("tr");
      const th = document.createElement("th");
      th.textContent = label;
      tr.appendChild(th);
      for (const [field, value, span] of cells) {
        const td = document.createElement("td");
        td.dataset.field = field;
        td.dataset.value = value === null || value === undefined ? "null" : String(value);
        td.textContent = formatNumber(value);
        if (span) td.colSpan = span;
        tr.appendChild(td);
      }
      parent.appendChild(tr);
    };
    for (const key of ["inflections", "vibrations", "e_s", "max_z"]) {
      row(measures, key, [[`before.${key}`, r.before[key]], [`after.${key}`, r.after[key]]]);
    }
    if (r.before.energies && r.after.energies) {
      for (const key of Object.keys(r.before.energies)) {
        row(measures, key, [[`before.energies.${key}`, r.before.energies[key]], [`after.energies.${key}`, r.after.energies[key]]]);
      }
    }
    row(run, "S_d", [["s_d", r.s_d, 2]]);
    row(run, "M_d", [["m_d", r.m_d, 2]]);
    row(run, "moved", [["moved", r.moved.length, 2]]);
    row(run, "iterations", [["iterations", r.iterations, 2]]);
    if (r.termination !== undefined) row(run, "termination", [["termination", r.termination, 2]]);
    row(run, "time (ms)", [["elapsed_ms", r.elapsed_ms, 2]]);
  }

  function renderLists() {
    $("bad-list").textContent = state.bad.length ? state.bad.join(", ") : "none";
    $("fixed-list").textContent = state.fixed.length ? state.fixed.join(", ") : "none";
    const list = $("history");
    list.textContent = "";
    state.history.forEach((entry, i) => {
      const item = document.createElement("li");
      const button = document.createElement("button");
      button.className = "link" + (i === state.index ? " current" : "");
      button.textContent = entry.label;
      button.addEventListener("click", () => go(i));
      item.appendChild(button);
      list.appendChild(item);
    });
  }

  function updateButtons() {
    const entry = current();
    $("undo").disabled = state.busy || state.index <= 0;
    $("redo").disabled = state.busy || state.index >= state.history.length - 1;
    $("download-points").disabled = !entry;
    $("download-report").disabled = !entry;
    $("download-cad").disabled = !entry || state.busy;
    $("fair-selected").disabled = state.busy || !entry || !state.bad.length;
    $("run-method").disabled = state.busy || !entry || !selectedMethod();
    document.body.dataset.history = String(state.history.length);
    document.body.dataset.index = String(state.index);
  }

  function render() {
    renderMain();
    renderBars();
    renderCurvature();
    renderReport();
    renderLists();
    updateButtons();
  }

  // ---------------------------------------------------------------- zoom, pan, clicks

  function installPointer() {
    const svg = $("main-view");
    let drag = null;
    svg.addEventListener("pointerdown", (e) => {
      if (e.button !== 0) return;
      drag = { x: e.clientX, y: e.clientY, px: state.view.px, py: state.view.py, moved: false, target: e.target };
    });
    svg.addEventListener("pointermove", (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (!drag.moved && Math.hypot(dx, dy) < 4) return;
      if (!drag.moved) svg.setPointerCapture(e.pointerId);
      drag.moved = true;
      state.view.px = drag.px + dx;
      state.view.py = drag.py + dy;
      renderMain();
    });
    const end = (e) => {
      if (!drag) return;
      const was = drag;
      drag = null;
      if (!was.moved && was.target && was.target.dataset && was.target.dataset.index !== undefined) {
        togglePoint(Number(was.target.dataset.index));
      }
      if (svg.hasPointerCapture && svg.hasPointerCapture(e.pointerId)) svg.releasePointerCapture(e.pointerId);
    };
    svg.addEventListener("pointerup", end);
    svg.addEventListener("pointercancel", () => { drag = null; });
    svg.addEventListener("wheel", (e) => {
      e.preventDefault();
      const box = svg.getBoundingClientRect();
      const mx = e.clientX - box.left - box.width / 2, my = e.clientY - box.top - box.height / 2;
      const f = Math.exp(-e.deltaY * 0.0015);
      const k = Math.min(Math.max(state.view.k * f, 0.2), 500);
      const g = k / state.view.k;
      state.view.px = mx - (mx - state.view.px) * g;
      state.view.py = my - (my - state.view.py) * g;
      state.view.k = k;
      renderMain();
    }, { passive: false });
    svg.addEventListener("dblclick", () => { state.view = { k: 1, px: 0, py: 0 }; renderMain(); });
    for (const id of ["z-view"]) {
      $(id).addEventListener("click", (e) => {
        const index = e.target.dataset && e.target.dataset.index;
        if (index !== undefined) togglePoint(Number(index));
      });
    }
  }

  function install() {
    $("dataset").addEventListener("change", (e) => loadDataset(e.target.value));
    $("upload").addEventListener("change", (e) => {
      const file = e.target.files && e.target.files[0];
      if (file) upload(file);
      e.target.value = "";
    });
    $("undo").addEventListener("click", () => go(state.index - 1));
    $("redo").addEventListener("click", () => go(state.index + 1));
    $("download-points").addEventListener("click", downloadPoints);
    $("download-report").addEventListener("click", downloadReport);
    $("download-cad").addEventListener("click", downloadCad);
    $("fair-selected").addEventListener("click", fairSelected);
    $("run-method").addEventListener("click", runMethod);
    $("method").addEventListener("change", () => { fillParams(); updateButtons(); });
    $("params").addEventListener("submit", (e) => { e.preventDefault(); runMethod(); });
    $("clear-bad").addEventListener("click", () => { state.bad = []; render(); });
    $("clear-fixed").addEventListener("click", () => { state.fixed = []; render(); });
    $("comb-scale").addEventListener("input", renderMain);
    $("reset-view").addEventListener("click", () => { state.view = { k: 1, px: 0, py: 0 }; renderMain(); });
    window.addEventListener("resize", () => { if (current()) render(); });
    document.addEventListener("keydown", (e) => {
      if (!(e.ctrlKey || e.metaKey) || e.target.tagName === "INPUT") return;
      const key = e.key.toLowerCase();
      if (key === "z" && !e.shiftKey) { e.preventDefault(); go(state.index - 1); }
      if ((key === "z" && e.shiftKey) || key === "y") { e.preventDefault(); go(state.index + 1); }
    });
    installPointer();
  }

  async function start() {
    install();
    await busy("loading the methods and data sets", async () => {
      const [methods, datasets] = await Promise.all([api("/api/methods"), api("/api/datasets")]);
      state.methods = methods.methods;
      state.defaults = methods.defaults;
      const select = $("dataset");
      // `fair serve FILE`: the page opens on the first file given (the embedded sets come first).
      state.firstFile = (datasets.datasets.find((d) => d.origin === "file") || {}).name;
      for (const d of datasets.datasets) {
        const option = document.createElement("option");
        option.value = d.name;
        option.textContent = d.name;
        option.title = d.about;
        select.appendChild(option);
      }
    });
    render();
    // `#dataset=NAME` in the address opens that data set (a link to a view).
    const wanted = new URLSearchParams(location.hash.slice(1)).get("dataset") || state.firstFile;
    if (wanted) {
      $("dataset").value = wanted;
      await loadDataset(wanted);
    }
  }

  // For tests and the curious: read-only views of the page's state.
  window.fairPage = {
    current: () => current(),
    history: () => state.history.map((e) => e.label),
    index: () => state.index,
    selection: () => ({ bad: state.bad.slice(), fixed: state.fixed.slice() }),
    constraints: () => constraints(true),
  };

  start();
})();
