// bodycheck: the scene players of a page (issue 31, item 2; identities/cli/scene_player.py
// projects every frame, this only moves the shapes).  No library, no file read: a saved
// page plays on its own.  ?frame=N in the address opens every player at its frame N.
"use strict";

(function () {
  const NS = "http://www.w3.org/2000/svg";

  function make(parent, tag, attrs) {
    const el = document.createElementNS(NS, tag);
    for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
    parent.appendChild(el);
    return el;
  }

  function pairs(flat) {
    const out = [];
    for (let i = 0; i < flat.length; i += 2) out.push(flat[i] + "," + flat[i + 1]);
    return out.join(" ");
  }

  function setup(root) {
    const data = JSON.parse(root.querySelector(".scene-data").textContent);
    const stage = root.querySelector(".stage");
    const slider = root.querySelector(".slider");
    const button = root.querySelector(".play");
    const time = root.querySelector(".time");
    const line = root.querySelector(".timeline");
    for (const q of data.planes) make(stage, "polygon", { class: "plane", points: pairs(q) });
    const group = make(stage, "g", { class: "bodies" });
    const shapes = data.frames[0].map((s) =>
      s.c ? make(group, "circle", { class: "body" }) : make(group, "polyline", { class: "body" })
    );
    const width = data.size[0];
    const x = (t) => (data.duration > 0 ? (t / data.duration) * (width - 8) + 4 : 4);
    make(line, "line", { x1: 4, y1: 12, x2: width - 4, y2: 12, stroke: "#999" });
    for (const ev of data.events) {
      const mark = make(line, "line", { class: "mark", x1: x(ev.t), y1: 3, x2: x(ev.t), y2: 21 });
      make(mark, "title", {}).textContent = ev.label;
    }
    const now = make(line, "circle", { class: "now", cx: 4, cy: 12, r: 4 });
    slider.max = String(data.frames.length - 1);

    function show(k) {
      const frame = data.frames[k];
      frame.forEach((s, i) => {
        if (s.c) {
          shapes[i].setAttribute("cx", s.c[0]);
          shapes[i].setAttribute("cy", s.c[1]);
          shapes[i].setAttribute("r", s.c[2]);
        } else {
          shapes[i].setAttribute("points", pairs(s.p));
        }
      });
      slider.value = String(k);
      time.textContent = "t = " + data.t[k].toPrecision(4) + " s";
      now.setAttribute("cx", x(data.t[k]));
      root.setAttribute("data-frame", String(k));
    }

    let timer = null;
    function stop() {
      if (timer !== null) clearInterval(timer);
      timer = null;
      button.textContent = "play";
    }
    button.addEventListener("click", () => {
      if (timer !== null) return stop();
      button.textContent = "pause";
      timer = setInterval(() => {
        const k = Number(slider.value) + 1;
        if (k >= data.frames.length) return stop();
        show(k);
      }, 40);
    });
    slider.addEventListener("input", () => {
      stop();
      show(Number(slider.value));
    });
    const asked = Number(new URLSearchParams(window.location.search).get("frame"));
    show(Number.isInteger(asked) && asked > 0 ? Math.min(asked, data.frames.length - 1) : 0);
  }

  function start() {
    document.querySelectorAll("section.scene").forEach(setup);
  }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
