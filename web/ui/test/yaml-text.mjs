// Unit test of web/ui/src/yaml-text.js, the structured edits of a model's YAML text: each edit
// changes only its value and keeps the user's comments, alignment and styles; the result is
// compared with the whole expected text. Exit 77 (ctest's skip) without web/ui's node_modules.
//   node web/ui/test/yaml-text.mjs
import assert from 'node:assert/strict';

let lib;
try {
  lib = await import('../src/yaml-text.js');
} catch (e) {
  console.log(`SKIP: ${e.message} (npm ci in web/ui)`);
  process.exit(77);
}
const { setIn, deleteIn, readModel, renamePoint, deletePoint, EditError } = lib;

const model = `# A four-bar (mm).
units: {length: mm}
points:
  O2: [0, 0]          # crank pivot
  O4: [200, 0]        # rocker pivot
  A:  [80, 0]
  B:  [181.25, 148.8]
ground: [O2, O4]
bodies:
  crank:   [O2, A]    # input
  coupler: [A, B]
  rocker:  [O4, B]
drivers:
  - {angle: crank, from: 0, to: 360, speed: 120 rpm}
`;

const cases = [];
const check = (name, got, want) => cases.push([name, got, want]);

// A coordinate: only the number changes, the comment keeps its column.
check('coordinate', setIn(model, ['points', 'O4', 0], 210.5), model.replace('O4: [200, 0]        #', 'O4: [210.5, 0]      #'));
// A whole point (as the drag writes it).
check('point', setIn(model, ['points', 'A'], [75, 5]), model.replace('A:  [80, 0]', 'A:  [75, 5]'));
// A new point, a new body, a ground entry: appended in the style of their neighbours.
check('new point', setIn(model, ['points', 'P1'], [-10, 20.5]), model.replace('  B:  [181.25, 148.8]\n', '  B:  [181.25, 148.8]\n  P1: [-10, 20.5]\n'));
check('new body', setIn(model, ['bodies', 'link1'], ['P1', 'A']), model.replace('  rocker:  [O4, B]\n', '  rocker:  [O4, B]\n  link1: [P1, A]\n'));
check('ground entry', setIn(model, ['ground', 2], 'P1'), model.replace('ground: [O2, O4]', 'ground: [O2, O4, P1]'));
check('ground removed', deleteIn(model, ['ground', 1]), model.replace('ground: [O2, O4]', 'ground: [O2]'));
// A driver's key in a flow mapping: set, added, removed; text values needing quotes get them.
check('driver to', setIn(model, ['drivers', 0, 'to'], 180), model.replace('to: 360', 'to: 180'));
check('driver name', setIn(model, ['drivers', 0, 'name'], 'in: put'), model.replace('120 rpm}', '120 rpm, name: "in: put"}'));
check('driver speed removed', deleteIn(model, ['drivers', 0, 'speed']), model.replace(', speed: 120 rpm', ''));
// A short-form body written in long form, its comment kept; then a property removed.
const long = setIn(model, ['bodies', 'crank'], { points: ['O2', 'A'], bar: { width: 16 }, thickness: 6, material: 'steel' });
check('long form', long, model.replace('  crank:   [O2, A]    # input\n', '  crank:\n    points: [O2, A]\n    bar: {width: 16}\n    thickness: 6\n    material: steel    # input\n'));
check('property removed', deleteIn(long, ['bodies', 'crank', 'bar']), model.replace('  crank:   [O2, A]    # input\n', '  crank:\n    points: [O2, A]\n    thickness: 6\n    material: steel    # input\n'));
// A new top-level section and a body removed with its line.
check('new section', setIn(model, ['gravity'], [0, -9.81]), `${model}gravity: [0, -9.81]\n`);
check('body removed', deleteIn(model, ['bodies', 'coupler']), model.replace('  coupler: [A, B]\n', ''));
// An empty section gets its first entry.
check('empty section', setIn('points:\n  A: [0, 0]\nforces:\n', ['forces', 0], { point: 'A', force: [0, -1] }), 'points:\n  A: [0, 0]\nforces: [{point: A, force: [0, -1]}]\n');
// JSON text is YAML too: edited in place.
check('json', setIn('{"points": {"A": [0, 0]}, "ground": ["A"]}', ['points', 'A', 1], 3), '{"points": {"A": [0, 3]}, "ground": ["A"]}');
// A point renamed: its key and every reference (ground, bodies, a slider, a force), comments kept.
const slider = `points:
  O: [0, 0]     # pivot
  A: [1, 0]
  C: [3, 0]     # pin
  Y: [9, 0]
ground: [O, Y]
bodies:
  crank: [O, A]
  rod: {points: [A, C], mass: 1}
  block: [C]
sliders:
  - {body: block, point: C, along: [O, Y]}
forces:
  - {point: C, force: [-10, 0]}
drivers:
  - {angle: crank, from: 0, to: 360}
`;
check('rename point', renamePoint(slider, 'C', 'Pin'), slider.replace('  C: [3, 0]     #', '  Pin: [3, 0]   #').replace('[A, C]', '[A, Pin]')
  .replace('block: [C]', 'block: [Pin]').replace('point: C,', 'point: Pin,').replace('{point: C', '{point: Pin'));
check('rename ground point', renamePoint(slider, 'O', 'O2'), slider.replace('  O: [0, 0]     #', '  O2: [0, 0]    #').replace('[O, Y]\nbodies', '[O2, Y]\nbodies')
  .replace('[O, A]', '[O2, A]').replace('along: [O, Y]', 'along: [O2, Y]'));
// A point deleted with its ground entry and its places in the bodies' lists (also long form).
check('delete point', deletePoint(model, 'B'), model.replace('  B:  [181.25, 148.8]\n', '').replace('coupler: [A, B]', 'coupler: [A]').replace('rocker:  [O4, B]', 'rocker:  [O4]'));
check('delete ground point', deletePoint(model, 'O4'), model.replace('  O4: [200, 0]        # rocker pivot\n', '').replace('ground: [O2, O4]', 'ground: [O2]').replace('rocker:  [O4, B]', 'rocker:  [B]'));

let failed = 0;
for (const [name, got, want] of cases) {
  try { assert.equal(got, want); } catch (e) { failed++; console.error(`FAIL ${name}:\n${e.message}`); }
}
// Every edited text still reads as the model it should be.
assert.deepEqual(readModel(setIn(model, ['points', 'P1'], [1, 2])).points.P1, [1, 2]);
// Broken YAML is refused with the parser's message, not edited blindly.
assert.throws(() => setIn('points: [1, 2', ['points', 0], 3), EditError);
// What a structured rename or delete cannot do safely is refused with the reason.
assert.throws(() => renamePoint(slider, 'C', 'crank'), /crank is the name of a body/);
assert.throws(() => renamePoint(slider, 'C', 'Y'), /already a point Y/);
assert.throws(() => renamePoint(slider, 'C', '2x'), /not a name/);
assert.throws(() => renamePoint(`${slider}torques:\n  - {body: rod, torque: "C*2"}\n`, 'C', 'D'), /C is mentioned in “C\*2”/);
assert.throws(() => renamePoint(slider.replace('to: 360}', 'to: 360, name: A}'), 'A', 'B'), /A is also the name of drivers/);
assert.throws(() => deletePoint(slider, 'C'), /C is used by sliders.point \(line 12\): remove that first/);
if (failed) process.exit(1);
console.log(`OK: ${cases.length} edits`);
