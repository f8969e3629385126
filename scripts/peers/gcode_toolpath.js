// Runs npm's gcode-toolpath (cncjs) over one G-code file and prints the number of moves, for
// scripts/bench-peers.sh. Usage: node gcode_toolpath.js FILE (NODE_PATH must find the package).
'use strict';
const fs = require('fs');
const Toolpath = require('gcode-toolpath');

let lines = 0;
let arcs = 0;
const toolpath = new Toolpath({
  addLine: () => { lines += 1; },
  addArcCurve: () => { arcs += 1; },
});
const text = fs.readFileSync(process.argv[2], 'utf8');
toolpath.loadFromStringSync(text);
console.log(JSON.stringify({ lines, arcs }));
