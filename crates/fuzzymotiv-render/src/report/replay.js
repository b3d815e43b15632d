// Replay widget of fuzzymotiv reports: draws a room top-down and replays the best robot's trial
// step by step (body, heading, the robot's IR readings, visited cells, action label).
// Data: the JSON in <script id="fm-data">; one widget per <div class="replay" data-replay="k">.
// For tests and curious readers, window.fuzzymotivReplays[k] holds each widget's live state
// (room, step, playing, x, y, heading, action) and the room canvas mirrors it in data-* attributes.
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("fm-data").textContent);
  var ACTION = { S: "straight", L: "left30", R: "right30", T: "turn180" };
  var ARROW = { S: "\u2191", L: "\u21b0", R: "\u21b1", T: "\u27f2" };
  var ACOLOUR = { S: "#4c78a8", L: "#54a24b", R: "#e45756", T: "#b279a2" };
  var SPEEDS = [0.25, 0.5, 1, 2, 4, 8];
  var CELL = 50;
  window.fuzzymotivReplays = [];

  function el(tag, attrs, parent) {
    var e = document.createElement(tag);
    Object.keys(attrs || {}).forEach(function (k) {
      if (k === "text") e.textContent = attrs[k];
      else if (k === "class") e.className = attrs[k];
      else e.setAttribute(k, attrs[k]);
    });
    if (parent) parent.appendChild(e);
    return e;
  }

  function mix(a, b, t) {
    var pa = [1, 3, 5].map(function (i) { return parseInt(a.substr(i, 2), 16); });
    var pb = [1, 3, 5].map(function (i) { return parseInt(b.substr(i, 2), 16); });
    return "rgb(" + pa.map(function (v, i) { return Math.round(v + (pb[i] - v) * t); }).join(",") + ")";
  }

  function sensorColour(v, max) { return mix("#c8c8c8", "#d62728", Math.min(1, Math.max(0, v / max))); }

  // Per-room derived data: bounds, cell of every pose, first visit of every cell.
  function prepare(room) {
    var xs = room.outline.map(function (p) { return p[0]; });
    var ys = room.outline.map(function (p) { return p[1]; });
    var lo = [Math.min.apply(null, xs), Math.min.apply(null, ys)];
    var hi = [Math.max.apply(null, xs), Math.max.apply(null, ys)];
    var cols = Math.max(1, Math.ceil((hi[0] - lo[0]) / CELL));
    var rows = Math.max(1, Math.ceil((hi[1] - lo[1]) / CELL));
    var first = {};
    var visitedAt = [];
    var count = 0;
    for (var t = 0; t < room.x.length; t++) {
      var i = Math.min(cols - 1, Math.max(0, Math.floor((room.x[t] - lo[0]) / CELL)));
      var j = Math.min(rows - 1, Math.max(0, Math.floor((room.y[t] - lo[1]) / CELL)));
      var k = j * cols + i;
      if (!(k in first)) { first[k] = t; count++; }
      visitedAt.push(count);
    }
    var walls = [];
    [room.outline].concat(room.obstacles).forEach(function (poly) {
      poly.forEach(function (p, k) { walls.push([p, poly[(k + 1) % poly.length]]); });
    });
    return { lo: lo, hi: hi, cols: cols, first: first, visitedAt: visitedAt, walls: walls };
  }

  // Distance along the ray from (ox, oy) in direction (dx, dy) to the nearest wall, at most max.
  function rayLength(walls, ox, oy, dx, dy, max) {
    var best = max;
    walls.forEach(function (w) {
      var ax = w[0][0], ay = w[0][1], ex = w[1][0] - ax, ey = w[1][1] - ay;
      var den = dx * ey - dy * ex;
      if (Math.abs(den) < 1e-12) return;
      var t = ((ax - ox) * ey - (ay - oy) * ex) / den;
      var u = ((ax - ox) * dy - (ay - oy) * dx) / den;
      if (t >= 0 && u >= 0 && u <= 1 && t < best) best = t;
    });
    return best;
  }

  function makeReplay(root, spec, index) {
    var robot = spec.robot;
    var state = { index: index, room: 0, step: 0, playing: false, speed: 2, x: 0, y: 0, heading: 0, action: "" };
    var rooms = spec.rooms.map(function (r) { r.prep = prepare(r); return r; });

    var controls = el("div", { class: "controls" }, root);
    var roomLabel = el("label", { text: "Room " }, controls);
    var roomSel = el("select", { class: "room-select", "aria-label": "room" }, roomLabel);
    rooms.forEach(function (r, k) { el("option", { value: k, text: r.room }, roomSel); });
    if (rooms.length < 2) roomLabel.style.display = "none";
    var play = el("button", { class: "play", type: "button", text: "\u25b6 Play" }, controls);
    var speedLabel = el("label", { text: "Speed " }, controls);
    var speedSel = el("select", { class: "speed", "aria-label": "speed" }, speedLabel);
    SPEEDS.forEach(function (s) {
      var o = el("option", { value: s, text: s + "\u00d7" + (s === 1 ? " (real time)" : "") }, speedSel);
      if (s === state.speed) o.selected = true;
    });
    var slider = el("input", { class: "slider", type: "range", min: 0, max: 1, value: 0, step: 1, "aria-label": "step" }, controls);
    var stepInfo = el("span", { class: "stepinfo" }, controls);

    var stage = el("div", { class: "stage" }, root);
    var left = el("div", {}, stage);
    var canvas = el("canvas", { class: "room" }, left);
    var strip = el("canvas", { class: "strip", title: "actions per step: click to jump" }, left);
    var legend = el("div", { class: "legend" }, left);
    legend.innerHTML = "Actions: " + ["S", "L", "R", "T"].map(function (a) {
      return "<i style=\"background:" + ACOLOUR[a] + "\"></i>" + ACTION[a];
    }).join("") + "<i style=\"background:#000\"></i>collision (below)";
    var side = el("div", { class: "side" }, stage);
    var actionEl = el("div", { class: "action" }, side);
    var collEl = el("div", {}, side);
    var MAX = robot.max;
    el("div", { text: "Infrared sensors of the " + robot.name + " (0 = nothing within reach, " + MAX + " = touching a wall):" }, side);
    var sbars = el("div", { class: "sbars" }, side);
    var sensorRows = robot.names.map(function (name) {
      el("span", { text: name }, sbars);
      var bar = el("div", { class: "sbar" }, sbars);
      var fill = el("span", {}, bar);
      var val = el("span", { class: "val" }, sbars);
      return { fill: fill, val: val };
    });
    el("div", { text: "Motor outputs (0.5 = stop, 1 = full speed forward, 0 = full speed back; orange = backwards):" }, side);
    var mbars = el("div", { class: "sbars" }, side);
    var motorRows = ["mL left wheel", "mR right wheel"].map(function (name) {
      el("span", { text: name }, mbars);
      var bar = el("div", { class: "sbar" }, mbars);
      var fill = el("span", {}, bar);
      var val = el("span", { class: "val" }, mbars);
      return { fill: fill, val: val };
    });
    var cellsEl = el("div", {}, side);
    var termsEl = el("div", { class: "note" }, side);

    var view = {};
    function layout() {
      var r = rooms[state.room];
      var w = r.prep.hi[0] - r.prep.lo[0], h = r.prep.hi[1] - r.prep.lo[1];
      var pad = 14;
      var scale = Math.min(560 / w, 440 / h);
      var cw = Math.round(w * scale + 2 * pad), ch = Math.round(h * scale + 2 * pad);
      var dpr = window.devicePixelRatio || 1;
      canvas.width = Math.round(cw * dpr); canvas.height = Math.round(ch * dpr);
      canvas.style.width = cw + "px"; canvas.style.height = ch + "px";
      var sw = Math.max(cw, 560);
      strip.width = Math.round(sw * dpr); strip.height = Math.round(26 * dpr);
      strip.style.width = sw + "px"; strip.style.height = "26px";
      view = { scale: scale, pad: pad, dpr: dpr, cw: cw, ch: ch, sw: sw };
      slider.max = r.steps;
      stepInfo.textContent = "";
      termsEl.textContent = "This run: a = " + r.terms.a.toFixed(3) + ", g = " + r.terms.g.toFixed(3) +
        ", b = " + r.terms.b.toFixed(3) + ", F = " + r.f.toFixed(3) +
        (r.online_l ? " with l = 0 (one run cannot measure recognition; the GA's F is in the table above)" : "") + " (" +
        (r.run === "all" ? "the robot evolved in all rooms" : "the robot evolved in " + r.run) + ").";
    }

    function px(r, x) { return view.pad + (x - r.prep.lo[0]) * view.scale; }
    function py(r, y) { return view.pad + (r.prep.hi[1] - y) * view.scale; }

    function polygon(ctx, r, pts) {
      ctx.beginPath();
      pts.forEach(function (p, k) {
        if (k === 0) ctx.moveTo(px(r, p[0]), py(r, p[1])); else ctx.lineTo(px(r, p[0]), py(r, p[1]));
      });
      ctx.closePath();
    }

    function draw() {
      var r = rooms[state.room];
      var t = state.step;
      var ctx = canvas.getContext("2d");
      ctx.setTransform(view.dpr, 0, 0, view.dpr, 0, 0);
      ctx.clearRect(0, 0, view.cw, view.ch);
      // floor and visited cells (the exploration term a counts them)
      polygon(ctx, r, r.outline);
      ctx.fillStyle = "#fafafa"; ctx.fill();
      ctx.save(); polygon(ctx, r, r.outline); ctx.clip();
      ctx.fillStyle = "rgba(44,160,44,0.18)";
      Object.keys(r.prep.first).forEach(function (k) {
        if (r.prep.first[k] > t) return;
        var i = k % r.prep.cols, j = Math.floor(k / r.prep.cols);
        var x = r.prep.lo[0] + i * CELL, y = r.prep.lo[1] + j * CELL;
        ctx.fillRect(px(r, x), py(r, y + CELL), CELL * view.scale, CELL * view.scale);
      });
      ctx.strokeStyle = "#eee"; ctx.lineWidth = 1;
      for (var gx = r.prep.lo[0]; gx <= r.prep.hi[0]; gx += CELL) {
        ctx.beginPath(); ctx.moveTo(px(r, gx), py(r, r.prep.lo[1])); ctx.lineTo(px(r, gx), py(r, r.prep.hi[1])); ctx.stroke();
      }
      for (var gy = r.prep.lo[1]; gy <= r.prep.hi[1]; gy += CELL) {
        ctx.beginPath(); ctx.moveTo(px(r, r.prep.lo[0]), py(r, gy)); ctx.lineTo(px(r, r.prep.hi[0]), py(r, gy)); ctx.stroke();
      }
      // home zone (clipped to the room, as the paper draws it)
      if (r.zone) {
        ctx.beginPath(); ctx.arc(px(r, r.zone[0]), py(r, r.zone[1]), r.zone[2] * view.scale, 0, 2 * Math.PI);
        ctx.fillStyle = "rgba(31,119,180,0.10)"; ctx.fill();
        ctx.strokeStyle = "rgba(31,119,180,0.6)"; ctx.setLineDash([5, 4]); ctx.lineWidth = 1.2; ctx.stroke(); ctx.setLineDash([]);
      }
      // the mission: goal zone (orange) and waypoints (purple, numbered), dashed like the home zone
      function disc(z, fill, line) {
        ctx.beginPath(); ctx.arc(px(r, z[0]), py(r, z[1]), z[2] * view.scale, 0, 2 * Math.PI);
        ctx.fillStyle = fill; ctx.fill();
        ctx.strokeStyle = line; ctx.setLineDash([5, 4]); ctx.lineWidth = 1.2; ctx.stroke(); ctx.setLineDash([]);
      }
      if (r.goal) {
        disc(r.goal, "rgba(255,127,14,0.12)", "rgba(255,127,14,0.8)");
        ctx.fillStyle = "#ff7f0e"; ctx.font = "bold 11px sans-serif"; ctx.textAlign = "center";
        ctx.fillText("goal", px(r, r.goal[0]), py(r, r.goal[1]) + 4); ctx.textAlign = "start";
      }
      (r.waypoints || []).forEach(function (w, k) {
        disc(w, "rgba(148,103,189,0.12)", "rgba(148,103,189,0.8)");
        ctx.fillStyle = "#9467bd"; ctx.font = "bold 11px sans-serif"; ctx.textAlign = "center";
        ctx.fillText(String(k + 1), px(r, w[0]), py(r, w[1]) + 4); ctx.textAlign = "start";
      });
      ctx.restore();
      r.obstacles.forEach(function (o) { polygon(ctx, r, o); ctx.fillStyle = "#999"; ctx.fill(); });
      polygon(ctx, r, r.outline);
      ctx.strokeStyle = "#222"; ctx.lineWidth = 3; ctx.stroke();
      // whole path (faint) and the path so far
      function path(upto, style, width) {
        ctx.beginPath();
        for (var k = 0; k <= upto; k++) {
          if (k === 0) ctx.moveTo(px(r, r.x[k]), py(r, r.y[k])); else ctx.lineTo(px(r, r.x[k]), py(r, r.y[k]));
        }
        ctx.strokeStyle = style; ctx.lineWidth = width; ctx.stroke();
      }
      path(r.steps, "rgba(0,0,0,0.13)", 1);
      path(t, "#1f77b4", 1.6);
      // home pose
      var home = r.home;
      ctx.beginPath(); ctx.arc(px(r, home[0]), py(r, home[1]), robot.radius * view.scale, 0, 2 * Math.PI);
      ctx.setLineDash([4, 3]); ctx.strokeStyle = "#2ca02c"; ctx.lineWidth = 1.5; ctx.stroke(); ctx.setLineDash([]);
      ctx.fillStyle = "#2ca02c"; ctx.font = "11px sans-serif";
      ctx.fillText("home", px(r, home[0]) - 12, py(r, home[1]) + robot.radius * view.scale + 12);
      // robot at step t: pose t, sensors read there (sensors[t]), action taken from there
      var x = r.x[t], y = r.y[t], h = r.h[t];
      var c = Math.cos(h), s = Math.sin(h);
      var reading = t < r.steps ? r.s[t] : null;
      robot.sensors.forEach(function (m, i) {
        var mx = x + c * m[0] - s * m[1], my = y + s * m[0] + c * m[1];
        var d = h + m[2] * Math.PI / 180;
        var v = reading ? reading[i] : 0;
        var len = rayLength(r.prep.walls, mx, my, Math.cos(d), Math.sin(d), m[3]);
        ctx.beginPath(); ctx.moveTo(px(r, mx), py(r, my));
        ctx.lineTo(px(r, mx + len * Math.cos(d)), py(r, my + len * Math.sin(d)));
        ctx.strokeStyle = sensorColour(v, MAX); ctx.lineWidth = 1 + 4 * v / MAX; ctx.stroke();
      });
      ctx.beginPath(); ctx.arc(px(r, x), py(r, y), robot.radius * view.scale, 0, 2 * Math.PI);
      ctx.fillStyle = "rgba(31,119,180,0.25)"; ctx.fill();
      ctx.strokeStyle = "#1f4e79"; ctx.lineWidth = 2; ctx.stroke();
      ctx.beginPath(); ctx.moveTo(px(r, x), py(r, y));
      ctx.lineTo(px(r, x + robot.radius * c), py(r, y + robot.radius * s));
      ctx.strokeStyle = "#1f4e79"; ctx.lineWidth = 2.5; ctx.stroke();
      // scale bar: 100 mm
      var sb = 100 * view.scale;
      ctx.strokeStyle = "#555"; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.moveTo(view.cw - view.pad - sb, view.ch - 4); ctx.lineTo(view.cw - view.pad, view.ch - 4); ctx.stroke();
      ctx.fillStyle = "#555"; ctx.textAlign = "right"; ctx.fillText("100 mm", view.cw - view.pad - sb - 4, view.ch - 1);
      ctx.textAlign = "left";
      drawStrip(r, t);
      updateSide(r, t);
      state.x = x; state.y = y; state.heading = h;
      state.action = t < r.steps ? ACTION[r.a[t]] : "";
      canvas.setAttribute("data-step", String(t));
      canvas.setAttribute("data-pose", x.toFixed(1) + "," + y.toFixed(1) + "," + h.toFixed(3));
      root.setAttribute("data-step", String(t));
    }

    function drawStrip(r, t) {
      var ctx = strip.getContext("2d");
      ctx.setTransform(view.dpr, 0, 0, view.dpr, 0, 0);
      ctx.clearRect(0, 0, view.sw, 26);
      var w = view.sw / Math.max(1, r.steps);
      for (var k = 0; k < r.steps; k++) {
        ctx.fillStyle = r.i && r.i.charAt(k) === "1" ? "#ddd" : ACOLOUR[r.a[k]];
        ctx.fillRect(k * w, 2, Math.max(1, w), 14);
        if (r.c.charAt(k) === "1") { ctx.fillStyle = "#000"; ctx.fillRect(k * w, 19, Math.max(1, w), 5); }
      }
      ctx.fillStyle = "#000"; ctx.fillRect(Math.min(view.sw - 2, t * w), 0, 2, 26);
    }

    function updateSide(r, t) {
      stepInfo.textContent = "step " + t + " / " + r.steps + "  (t = " + (t * robot.dt).toFixed(1) + " s)";
      if (t < r.steps && r.i && r.i.charAt(t) === "1") {
        actionEl.textContent = "idle: the trial ended at home after step " + r.executed;
        collEl.textContent = "";
      } else if (t < r.steps) {
        var a = r.a[t];
        actionEl.innerHTML = "";
        el("span", { class: "arrow", text: ARROW[a] }, actionEl).style.color = ACOLOUR[a];
        el("span", { text: " action: " + ACTION[a] }, actionEl);
        collEl.textContent = r.c.charAt(t) === "1" ? "collision: the move was blocked by a wall (heading still changed)" : "";
        collEl.className = r.c.charAt(t) === "1" ? "collision" : "";
      } else {
        actionEl.textContent = "end of the trial";
        collEl.textContent = "";
      }
      var reading = t < r.steps ? r.s[t] : null;
      sensorRows.forEach(function (row, i) {
        var v = reading ? reading[i] : 0;
        row.fill.style.width = (100 * v / MAX).toFixed(1) + "%";
        row.fill.style.background = sensorColour(Math.max(v, 0.3 * MAX), MAX);
        row.val.textContent = reading ? String(v) : "\u2013";
      });
      var m = t < r.steps ? r.m[t] : null;
      motorRows.forEach(function (row, i) {
        var v = m ? m[i] : 0.5;
        row.fill.style.width = (100 * v).toFixed(1) + "%";
        row.fill.style.background = v >= 0.5 ? "#1f77b4" : "#ff7f0e";
        row.val.textContent = m ? v.toFixed(2) : "\u2013";
      });
      cellsEl.textContent = "Cells of 50 mm entered so far: " + r.prep.visitedAt[t] + " (green).";
    }

    function setStep(t) {
      var r = rooms[state.room];
      state.step = Math.max(0, Math.min(r.steps, t | 0));
      slider.value = state.step;
      draw();
    }

    var raf = 0, last = null, acc = 0;
    function frame(ts) {
      raf = 0;
      if (!state.playing) return;
      if (last === null) last = ts;
      acc += (ts - last) / 1000 * state.speed / robot.dt;
      last = ts;
      var n = Math.floor(acc);
      if (n > 0) {
        acc -= n;
        var r = rooms[state.room];
        setStep(state.step + n);
        if (state.step >= r.steps) { pause(); return; }
      }
      raf = requestAnimationFrame(frame);
    }
    function start() {
      var r = rooms[state.room];
      if (state.step >= r.steps) setStep(0);
      state.playing = true; last = null; acc = 0;
      play.textContent = "\u275a\u275a Pause";
      root.setAttribute("data-playing", "true");
      if (!raf) raf = requestAnimationFrame(frame);
    }
    function pause() {
      state.playing = false;
      play.textContent = "\u25b6 Play";
      root.setAttribute("data-playing", "false");
    }

    play.addEventListener("click", function () { if (state.playing) pause(); else start(); });
    speedSel.addEventListener("change", function () { state.speed = +speedSel.value; });
    slider.addEventListener("input", function () { setStep(+slider.value); });
    roomSel.addEventListener("change", function () {
      pause(); state.room = +roomSel.value; layout(); setStep(0);
    });
    strip.addEventListener("click", function (e) {
      var r = rooms[state.room];
      var rect = strip.getBoundingClientRect();
      setStep(Math.round((e.clientX - rect.left) / rect.width * r.steps));
    });
    root.tabIndex = 0;
    root.addEventListener("keydown", function (e) {
      if (e.target !== root) return;
      if (e.key === " ") { e.preventDefault(); if (state.playing) pause(); else start(); }
      if (e.key === "ArrowRight") { e.preventDefault(); setStep(state.step + 1); }
      if (e.key === "ArrowLeft") { e.preventDefault(); setStep(state.step - 1); }
    });

    layout();
    setStep(0);
    state.play = start;
    state.pause = pause;
    state.setStep = setStep;
    return state;
  }

  var roots = document.querySelectorAll(".replay[data-replay]");
  for (var k = 0; k < roots.length; k++) {
    var spec = data.replays[+roots[k].getAttribute("data-replay")];
    window.fuzzymotivReplays.push(makeReplay(roots[k], spec, k));
  }
})();
