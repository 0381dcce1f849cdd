// Structured edits of a model's YAML text that keep everything else of the text as the user wrote
// it (comments, alignment, quoting, flow or block style): the text is parsed with the `yaml`
// package's Document API only to find where each node lies, and the edit splices that span.
// Re-printing the whole document (doc.toString()) would have re-flowed the user's file.
import { parseDocument, isMap, isSeq, isScalar, isPair, isAlias } from 'yaml';

export class EditError extends Error {}

// The model as the Document API reads it, or an EditError when the text is not valid YAML (the
// user is then told to fix the text first: an edit cannot be placed in broken YAML).
export function parseModel(text) {
  const doc = parseDocument(text, { uniqueKeys: false });
  if (doc.errors.length) throw new EditError(doc.errors[0].message.split('\n')[0]);
  return doc;
}

const plainKey = /^[A-Za-z_][\w.-]*$/;
const plainNumber = /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/;
const reserved = /^(~|null|true|false|yes|no|on|off|y|n)$/i;

function scalarSource(v, inFlow) {
  if (typeof v === 'number') return Number.isFinite(v) ? String(v) : JSON.stringify(String(v));
  if (typeof v === 'boolean') return String(v);
  const s = String(v);
  const special = inFlow ? /[,[\]{}#]|: |^[-?:!&*|>'"%@`]|^\s|\s$/ : /[#]|: |^[-?:!&*|>'"%@`[{]|^\s|\s$/;
  if (s === '' || reserved.test(s) || plainNumber.test(s) || special.test(s)) return JSON.stringify(s);
  return s;
}
function keySource(k) { return plainKey.test(String(k)) && !reserved.test(String(k)) ? String(k) : JSON.stringify(String(k)); }

// A value in flow style: [a, b], {k: v}, scalars.
function flowSource(v) {
  if (Array.isArray(v)) return `[${v.map(flowSource).join(', ')}]`;
  if (v && typeof v === 'object') return `{${Object.entries(v).map(([k, x]) => `${keySource(k)}: ${flowSource(x)}`).join(', ')}}`;
  return scalarSource(v, true);
}
// What follows `key:` in block context: " value" on the same line, or for a mapping its pairs on
// the next lines, one indentation step deeper (lists stay in flow style: [O2, A]).
// Mappings nested deeper, and the items of lists, stay in flow style: bar: {width: 20}.
function afterColon(v, indent, nested = false) {
  const deeper = `${indent}  `;
  if (!nested && Array.isArray(v) && v.length && v.every((x) => x && typeof x === 'object' && !Array.isArray(x))) {
    return v.map((x) => `\n${deeper}- ${flowSource(x)}`).join('');
  }
  if (!nested && v && typeof v === 'object' && !Array.isArray(v)) {
    return Object.entries(v).map(([k, x]) => `\n${deeper}${keySource(k)}:${afterColon(x, deeper, true)}`).join('');
  }
  return ` ${flowSource(v)}`;
}

function lineStart(text, at) { return text.lastIndexOf('\n', at - 1) + 1; }
function lineEnd(text, at) { const i = text.indexOf('\n', at); return i < 0 ? text.length : i; }
function columnOf(text, at) { return at - lineStart(text, at); }
// Replaces text[from, to) by `insert`; a comment later on the same line stays at its column
// (aligned comments are common in model files: `A:  [80, 0]      # crank pin`).
function splice(text, from, to, insert) {
  const after = text.slice(to, lineEnd(text, to));
  const gap = /^([^#'"]*?)( +)#/.exec(after);
  if (!gap || insert.includes('\n')) return text.slice(0, from) + insert + text.slice(to);
  const spaces = Math.max(1, gap[2].length - (insert.length - (to - from)));
  return text.slice(0, from) + insert + gap[1] + ' '.repeat(spaces) + text.slice(to + gap[0].length - 1);
}

// The end of the line where a node ends (a block node's span already holds its last newline).
function endOfEntry(text, node) {
  const at = node.range[1];
  return lineEnd(text, at > 0 && text[at - 1] === '\n' ? at - 1 : at);
}

function isNull(node) { return !node || (isScalar(node) && node.value === null); }
function nest(path, value) { return path.reduceRight((v, k) => (typeof k === 'number' ? [v] : { [k]: v }), value); }
function sameKey(pair, key) { return isScalar(pair.key) && String(pair.key.value) === String(key); }

// Appends `key: value` to a mapping node (flow: before its closing brace; block: on a new line
// after its last pair, at the pairs' indentation).
function appendPair(text, map, key, value, inFlow) {
  const last = map.items.at(-1);
  if (map.flow || inFlow) {
    const entry = `${keySource(key)}: ${flowSource(value)}`;
    if (!last) { const open = text.indexOf('{', map.range[0]); return splice(text, open + 1, open + 1, entry); }
    const end = last.value ? last.value.range[1] : last.key.range[1];
    return splice(text, end, end, `, ${entry}`);
  }
  const indent = ' '.repeat(columnOf(text, map.items[0].key.range[0]));
  const end = endOfEntry(text, isNull(last.value) ? last.key : last.value);
  return splice(text, end, end, `\n${indent}${keySource(key)}:${afterColon(value, indent)}`);
}
function appendItem(text, seq, value, inFlow) {
  const last = seq.items.at(-1);
  if (seq.flow || inFlow) {
    if (!last) { const open = text.indexOf('[', seq.range[0]); return splice(text, open + 1, open + 1, flowSource(value)); }
    return splice(text, last.range[1], last.range[1], `, ${flowSource(value)}`);
  }
  const indent = ' '.repeat(columnOf(text, seq.range[0]));
  const end = endOfEntry(text, last);
  return splice(text, end, end, `\n${indent}- ${flowSource(value)}`);
}
// Replaces the value of `pair` (which may be empty: `drivers:` and nothing).
function replaceValue(text, pair, value, inFlow) {
  const colon = text.indexOf(':', pair.key.range[1]);
  const from = isNull(pair.value) ? colon + 1 : pair.value.range[0];
  const to = isNull(pair.value) ? colon + 1 : pair.value.range[1];
  if (inFlow || !value || typeof value !== 'object' || Array.isArray(value)) {
    return splice(text, from, to, (isNull(pair.value) ? ' ' : '') + flowSource(value));
  }
  const indent = ' '.repeat(columnOf(text, pair.key.range[0]));
  return splice(text, colon + 1, Math.max(to, colon + 1), afterColon(value, indent));
}

// The text with the value at `path` (keys and list indices from the top) set to `value` (plain
// numbers, text, arrays and objects). Missing mappings along the path are created; an index one
// past a list's end appends.
export function setIn(text, path, value) {
  const doc = parseModel(text);
  let node = doc.contents;
  let inFlow = false;
  if (isNull(node)) return `${text.replace(/\s*$/, '')}${text.trim() ? '\n' : ''}${keySource(path[0])}:${afterColon(nest(path.slice(1), value), '')}\n`;
  for (let i = 0; i < path.length; i++) {
    const key = path[i];
    const rest = nest(path.slice(i + 1), value);
    if (isMap(node)) {
      const pair = node.items.find((p) => sameKey(p, key));
      if (!pair) return appendPair(text, node, key, rest, inFlow);
      if (isNull(pair.value) || i === path.length - 1) return replaceValue(text, pair, rest, inFlow || node.flow);
      inFlow = inFlow || node.flow;
      node = pair.value;
    } else if (isSeq(node)) {
      if (typeof key !== 'number') throw new EditError(`${path.slice(0, i).join('.')} is a list`);
      if (key >= node.items.length) return appendItem(text, node, rest, inFlow);
      inFlow = inFlow || node.flow;
      const item = node.items[key];
      if (i === path.length - 1 || isNull(item)) {
        return splice(text, item.range[0], item.range[1], flowSource(rest));
      }
      node = item;
    } else {
      throw new EditError(`${path.slice(0, i).join('.')} is not a mapping or list`);
    }
  }
  return text;
}

// The text without the entry at `path` (a mapping's pair or a list's item); the text unchanged
// when there is none.
export function deleteIn(text, path) {
  const doc = parseModel(text);
  const parent = path.length > 1 ? doc.getIn(path.slice(0, -1), true) : doc.contents;
  const key = path.at(-1);
  const items = parent?.items ?? [];
  const k = isMap(parent) ? items.findIndex((p) => sameKey(p, key)) : (isSeq(parent) ? key : -1);
  if (k < 0 || k >= items.length) return text;
  const span = (it) => (isPair(it) ? [it.key.range[0], (it.value ?? it.key).range[1]] : [it.range[0], it.range[1]]);
  const [from, to] = span(items[k]);
  if (parent.flow) {
    if (items.length === 1) return splice(text, from, to, '');
    if (k > 0) return splice(text, span(items[k - 1])[1], to, '');
    return splice(text, from, span(items[k + 1])[0], '');
  }
  // Block style: the whole lines of the entry (a list item's "- " included).
  const start = lineStart(text, from);
  const stop = endOfEntry(text, isPair(items[k]) ? (isNull(items[k].value) ? items[k].key : items[k].value) : items[k]);
  return splice(text, start, Math.min(stop + 1, text.length), '');
}

// The model read as plain data, for the tables (null when the text is not valid YAML).
export function readModel(text) {
  try { return parseModel(text).toJS({ maxAliasCount: 100 }) ?? {}; } catch { return null; }
}

// A number for the text, rounded to what the drawing's scale can show.
export function roundTo(v, digits) { return +(+v).toFixed(Math.max(0, Math.min(6, digits))); }

// ------------------------------------------------------------------------------ point names

const pointName = /^[A-Za-z_]\w*$/;
const lineOf = (text, at) => text.slice(0, at).split('\n').length;
const wordIn = (name, s) => new RegExp(`(^|[^\\w.])${name.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}($|[^\\w])`).test(s);

// Every place of the model that names point `name`: {path, node, key} for the points key itself
// and each scalar equal to it. Throws an EditError when the name is also something else's name
// (a body, a material, a driver), or is mentioned inside a longer text (a law, a note) where no
// structured edit can tell a reference from a coincidence: the user then edits by hand.
function pointReferences(text, doc, name) {
  const refs = [];
  const refuse = (node, why) => { throw new EditError(`${why} (line ${lineOf(text, node.range[0])})`); };
  const visit = (node, path) => {
    if (isAlias(node)) refuse(node, `an alias (*${node.source}) may stand for ${name}`);
    if (isMap(node)) {
      for (const pair of node.items) {
        const key = isScalar(pair.key) ? String(pair.key.value) : null;
        if (key === name) {
          if (path.length === 1 && path[0] === 'points') refs.push({ path: [...path, key], node: pair.key, key: true });
          else refuse(pair.key, `${name} is also the name of ${path.length ? `an entry of ${path.join('.')}` : 'a section'}`);
        }
        // The model's own title and description are prose, not references.
        if (path.length === 0 && (key === 'name' || key === 'description')) continue;
        if (key === 'name' && isScalar(pair.value) && String(pair.value.value) === name) refuse(pair.value, `${name} is also the name of ${path.join('.')}`);
        if (pair.value) visit(pair.value, [...path, key]);
      }
    } else if (isSeq(node)) {
      node.items.forEach((item, i) => visit(item, [...path, i]));
    } else if (isScalar(node) && typeof node.value === 'string') {
      if (node.value === name) refs.push({ path, node, key: false });
      else if (wordIn(name, node.value)) refuse(node, `${name} is mentioned in “${node.value}”: rename it by hand in the editor`);
    }
  };
  visit(doc.contents, []);
  return refs;
}

// The text with point `from` renamed `to` everywhere the model names it (its entry in points,
// ground, bodies, joints, drivers, loads...), each name replaced where it is written; an
// EditError when the rename cannot be done safely.
export function renamePoint(text, from, to) {
  const doc = parseModel(text);
  const points = doc.get('points');
  if (!isMap(points) || !points.has(from)) throw new EditError(`there is no point ${from}`);
  if (!pointName.test(to)) throw new EditError(`“${to}” is not a name: a letter or _ first, then letters, digits or _`);
  if (to === from) return text;
  if (points.has(to)) throw new EditError(`there is already a point ${to}`);
  const bodies = doc.get('bodies');
  if (isMap(bodies) && bodies.has(to)) throw new EditError(`${to} is the name of a body`);
  const refs = pointReferences(text, doc, from);
  let out = text;
  for (const r of refs.sort((a, b) => b.node.range[0] - a.node.range[0])) {
    out = splice(out, r.node.range[0], r.node.range[1], r.key ? keySource(to) : scalarSource(to, true));
  }
  return out;
}

// The text without point `name`: its entry in points, in ground and in the bodies' point lists.
// An EditError when something else uses it (a slider, a driver, a load...): that goes first.
export function deletePoint(text, name) {
  const doc = parseModel(text);
  const refs = pointReferences(text, doc, name);
  const removable = (p) => (p[0] === 'points' && p.length === 2) || (p[0] === 'ground' && p.length === 2)
    || (p[0] === 'bodies' && (p.length === 3 || (p.length === 4 && p[2] === 'points')));
  const other = refs.find((r) => !removable(r.path));
  if (other) throw new EditError(`${name} is used by ${other.path.filter((k) => typeof k === 'string').join('.')} (line ${lineOf(text, other.node.range[0])}): remove that first`);
  // Last first, so that the list indices of the entries still to delete stay right.
  let out = text;
  for (const r of refs.sort((a, b) => b.node.range[0] - a.node.range[0])) out = deleteIn(out, r.path);
  return out;
}
