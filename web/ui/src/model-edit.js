// Structured edits of the model on screen: the canvas tools, the Model tables and the body panel
// all change the editor's YAML text (yaml-text.js), never a private copy of the model, and then
// ask the server to check and solve it as for typed edits. Undo and redo are the editor's own
// history, so typed and structured edits undo in the order they were made.
import { undo, redo, isolateHistory } from '@codemirror/commands';
import { t } from './i18n.js';
import { readModel, setIn } from './yaml-text.js';

let ctx = null;

// ctx: {editor, state, analyse, status, showTab, setFrame, play} from main.js.
export function initModelEdit(context) {
  ctx = context;
  document.addEventListener('keydown', (e) => {
    if (!(e.ctrlKey || e.metaKey) || e.altKey || e.key.toLowerCase() !== 'z') return;
    // In the editor, CodeMirror's own keymap does it; in a table's field, the field's own undo.
    if (e.target.closest?.('.cm-editor, input, textarea, select')) return;
    e.preventDefault();
    if (e.shiftKey) redoEdit(); else undoEdit();
  });
  return ctx;
}
export function editContext() { return ctx; }
export function modelText() { return ctx.editor.state.doc.toString(); }
export function modelData() { return readModel(modelText()); }

// Applies change(text) -> text to the editor as one undo step and analyses the result. The
// editor gets only the changed span, so its scroll position and the rest of the text stay.
export function applyEdit(change) {
  const before = modelText();
  let after;
  try {
    after = change(before);
  } catch (e) {
    ctx.status(t('editFailed', e.message), true);
    return false;
  }
  if (after === before) return false;
  after = withUnits(after);
  let a = 0;
  while (a < before.length && a < after.length && before[a] === after[a]) a++;
  let b = 0;
  while (b < before.length - a && b < after.length - a && before[before.length - 1 - b] === after[after.length - 1 - b]) b++;
  ctx.editor.dispatch({
    changes: { from: a, to: before.length - b, insert: after.slice(a, after.length - b) },
    annotations: isolateHistory.of('full'),
    userEvent: 'input.structured',
  });
  ctx.analyse();
  return true;
}

// Every model the tools write says its units: a text without `units:` gets the unit of the
// drawing on screen (what its scale bar says; mm when nothing is drawn), so that points tapped on
// a drawing in mm are never read as metres, the reader's default.
function withUnits(text) {
  const m = readModel(text);
  if (!m || typeof m !== 'object' || Array.isArray(m) || m.units !== undefined) return text;
  try {
    return setIn(text, ['units'], { length: ctx.state.drawnUnit ?? 'mm', angle: 'deg' });
  } catch {
    return text;
  }
}

export function undoEdit() { if (undo(ctx.editor)) ctx.analyse(); }
export function redoEdit() { if (redo(ctx.editor)) ctx.analyse(); }

// A name not yet used among `taken`: P1, P2, ... or link1, link2, ...
export function freshName(prefix, taken) {
  for (let i = 1; ; i++) if (!taken.has(`${prefix}${i}`)) return `${prefix}${i}`;
}
