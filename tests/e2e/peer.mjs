// The peer of the web benchmark (`bench-web.mjs`): npm's `gcode-preview` (three.js, the most
// used web G-code previewer) given the same program in the same headless Chromium, timed from
// the call until its first full frame is on the canvas. gcode-preview reads a line's first word
// as its command, so the program's `N` words are dropped for it, and its feed moves are drawn
// as its extrusion (`nonTravelMoves`), its rapids as travel.

import path from "node:path";
import { fileURLToPath } from "node:url";

const MODULES = path.join(path.dirname(fileURLToPath(import.meta.url)), "node_modules");

/** Milliseconds gcode-preview takes from `program` to its first frame drawn, in a new page. */
export async function gcodePreviewMs(context, program) {
  const page = await context.newPage();
  try {
    await page.setContent('<canvas id="c" width="1600" height="757"></canvas>');
    await page.addScriptTag({ path: path.join(MODULES, "three/build/three.min.js") });
    await page.addScriptTag({ path: path.join(MODULES, "gcode-preview/dist/gcode-preview.js") });
    const text = program.replace(/^N\d+ /gm, "");
    return await page.evaluate((gcode) => {
      const canvas = document.getElementById("c");
      const t0 = performance.now();
      const preview = window.GCodePreview.init({
        canvas,
        renderTravel: true,
        nonTravelMoves: ["g1", "g01", "g2", "g02", "g3", "g03"],
      });
      preview.processGCode(gcode);
      preview.render();
      // Reading a pixel waits until the GPU has drawn the frame.
      const gl = preview.renderer.getContext();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
      return performance.now() - t0;
    }, text);
  } finally {
    await page.close();
  }
}
