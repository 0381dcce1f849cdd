// The core's messages (model errors, the sweep's warnings and stop, the check's Grashof classes,
// joints and Newton start) in the language chosen. The core speaks English, the same text in the
// CLI, Python and the API; this catalogue gives each message a stable code and its parameters
// by its English template, and says it again from a template per language. A message no
// template matches is shown as the core wrote it: English is the fallback, never a blank.
//
// A template is the core's text with {name} for each parameter; {name:msg} is a parameter that
// is itself a message of the core (translated in turn), {name:word} one of the words below
// (branch names, "turn"/"move"), {name:list} a list of names whose last "or" is said in the
// language. Names from the model (points, bodies, drivers, units, numbers)
// are parameters and pass through unchanged.
import { getLang } from './i18n.js';

const messages = [
  // Model errors (invalid_model), the ones a student meets first.
  ['unknown_point', "unknown point '{name}' (points are: {names})", "punto desconocido '{name}' (los puntos son: {names})"],
  ['unknown_point_in', "unknown point '{name}' in {where:word}", "punto desconocido '{name}' en {where}"],
  ['unknown_key_top', "unknown key '{key}' at the top level; did you mean '{hint}'?", "clave desconocida '{key}' en el nivel superior; ¿quería decir '{hint}'?"],
  ['unknown_key_top_plain', "unknown key '{key}' at the top level", "clave desconocida '{key}' en el nivel superior"],
  ['unknown_key_in_hint', "unknown key '{key}' in {where:word}; did you mean '{hint}'?", "clave desconocida '{key}' en {where}; ¿quería decir '{hint}'?"],
  ['unknown_key_in', "unknown key '{key}' in {where:word}", "clave desconocida '{key}' en {where}"],
  ['unknown_body_hint', "unknown body '{name}'; did you mean '{hint}'?", "cuerpo desconocido '{name}'; ¿quería decir '{hint}'?"],
  ['unknown_body', "unknown body '{name}'", "cuerpo desconocido '{name}'"],
  ['unknown_length_unit', "unknown length unit '{unit}' (use {units:list})", "unidad de longitud desconocida '{unit}' (use {units})"],
  ['unknown_angle_unit', "unknown angle unit '{unit}' (use {units:list})", "unidad de ángulo desconocida '{unit}' (use {units})"],
  ['needs_speed_unit', "'{value}' needs a unit per time such as {units:list}", "'{value}' necesita una unidad por tiempo, como {units}"],
  ['not_a_number', '{what} must be a number, not {value}', '{what} debe ser un número, no {value}'],
  ['defined_twice', "point '{name}' is defined twice (first given on line {line})", "el punto '{name}' está definido dos veces (la primera en la línea {line})"],
  ['lengths_two_points', "body '{name}' has {n} points: `lengths` applies only to bodies with two points", "el cuerpo '{name}' tiene {n} puntos: `lengths` solo se aplica a cuerpos de dos puntos"],
  ['driver_count', 'the mechanism has {dof} degree of freedom (Gruebler-Kutzbach count: {count}) but {drivers} drivers are given; add one driver per free input',
    'el mecanismo tiene {dof} grado de libertad (recuento de Grübler-Kutzbach: {count}) pero se dan {drivers} accionamientos; añada un accionamiento por cada entrada libre'],
  ['driver_count_plural', 'the mechanism has {dof} degrees of freedom (Gruebler-Kutzbach count: {count}) but {drivers} drivers are given; add one driver per free input',
    'el mecanismo tiene {dof} grados de libertad (recuento de Grübler-Kutzbach: {count}) pero se dan {drivers} accionamientos; añada un accionamiento por cada entrada libre'],
  ['driver_count_one', 'the mechanism has {dof} degree of freedom (Gruebler-Kutzbach count: {count}) but {drivers} driver is given; add one driver per free input',
    'el mecanismo tiene {dof} grado de libertad (recuento de Grübler-Kutzbach: {count}) pero se da {drivers} accionamiento; añada un accionamiento por cada entrada libre'],
  ['driver_count_plural_one', 'the mechanism has {dof} degrees of freedom (Gruebler-Kutzbach count: {count}) but {drivers} driver is given; add one driver per free input',
    'el mecanismo tiene {dof} grados de libertad (recuento de Grübler-Kutzbach: {count}) pero se da {drivers} accionamiento; añada un accionamiento por cada entrada libre'],
  ['yaml_unclosed', "invalid YAML: this '{open}' is never closed by a '{close}' ({detail})", "YAML no válido: este '{open}' no se cierra nunca con un '{close}'"],
  ['yaml_tab', 'invalid YAML: tab characters are not allowed in YAML indentation; indent with spaces', 'YAML no válido: no se admiten tabuladores en la sangría del YAML; sangre con espacios'],
  ['yaml', 'invalid YAML: {detail}', 'YAML no válido: {detail}'],
  // Assembly (cannot_assemble).
  ['cannot_assemble', 'cannot assemble the drawn pose with the given lengths: {reason:msg}', 'no se puede montar la posición dibujada con las longitudes dadas: {reason}'],
  ['constraint_unmet', "constraint '{constraint:msg}' cannot be met (off by {off})", "la restricción «{constraint}» no se puede cumplir (con un error de {off})"],
  ['length_of', 'length of {body} ({points})', 'longitud de {body} ({points})'],
  // The constraints' labels (Explain's equations, the assembly's errors).
  ['shape_of', 'shape of {body} ({point}, {axis})', 'forma de {body} ({point}, {axis})'],
  ['on_line', '{point} of {body} on the line {line}', '{point} de {body} sobre la recta {line}'],
  ['orientation_of', 'orientation of {body} along {line}', 'orientación de {body} a lo largo de {line}'],
  ['in_slot', '{point} in the slot {line}', '{point} en la ranura {line}'],
  ['driver_row', 'driver {name}', 'accionamiento {name}'],
  ['cannot_reach', "cannot reach the drivers' starting values from the drawn pose on its branch", 'no se alcanzan los valores iniciales de los accionamientos desde la posición dibujada en su rama'],
  // The sweep's stop (stop_reason) and warnings.
  ['sweep_stopped', 'sweep stopped between steps {a} and {b} at {at}: {why:msg}', 'barrido detenido entre los pasos {a} y {b} en {at}: {why}'],
  ['singular_position', 'the constraints cannot be followed past this point: a singular position, either a limit (toggle) that the input cannot pass or a change point where two branches cross (reciprocal condition of the Jacobian {rcond})',
    'las restricciones no se pueden seguir más allá de este punto: una posición singular, o bien un límite (agarrotamiento) que la entrada no puede pasar, o bien un punto de cambio donde se cruzan dos ramas (condición recíproca del jacobiano {rcond})'],
  ['no_kinetics', 'the model has no masses or loads (no `mass`, material, gravity, forces, torques or springs): every joint force and driver effort is zero',
    'el modelo no tiene masas ni cargas (ni `mass`, material, gravedad, fuerzas, pares o muelles): todas las fuerzas en las juntas y los esfuerzos de los accionamientos son nulos'],
  ['forces_not_unique', 'the mechanism has redundant constraints: its joint forces are not unique (statically indeterminate); the minimum-norm set is given',
    'el mecanismo tiene restricciones redundantes: sus fuerzas en las juntas no son únicas (hiperestático); se da el conjunto de norma mínima'],
  ['branch_changed', 'four-bar loop {loop} changed branch {where:msg} (now {branch:word})', 'el lazo de cuatro barras {loop} cambió de rama {where} (ahora {branch})'],
  ['between_steps', 'between steps {a} and {b}', 'entre los pasos {a} y {b}'],
  ['change_point_passed', 'passed a singular (change-point) position {where:msg} near {at}: the assembly branch may have changed there',
    'pasó por una posición singular (punto de cambio) {where} cerca de {at}: la rama de montaje puede haber cambiado ahí'],
  ['change_point_rocking', 'the rocking path passes a singular (change-point) position at {at} ({involved}): the assembly branch may change there',
    'el camino oscilante pasa por una posición singular (punto de cambio) en {at} ({involved}): la rama de montaje puede cambiar ahí'],
  ['input_limited', 'the sweep asks {driver} to {verb:word} {amount}, from {from} to {to}, but {who} lets it {verb2:word} {range} (limit positions): the sweep will stop at {stop}: {involved}',
    'el barrido pide a {driver} {verb} {amount}, de {from} a {to}, pero {who} le deja {verb2} {range} (posiciones límite): el barrido se detendrá en {stop}: {involved}'],
  ['many_turns', 'the sweep turns {driver} {turns} times, from {from} to {to}{hint}', 'el barrido gira {driver} {turns} veces, de {from} a {to}{hint}'],
  // The check: joints (the Model tab's list) and the Newton start (Explain).
  ['revolute', 'revolute {point} ({bodies})', 'par de rotación {point} ({bodies})'],
  ['start_drawn', 'the drawn pose', 'la posición dibujada'],
  ['start_step', "step {step}'s pose", 'la posición del paso {step}'],
];

// Words the core puts inside its messages, by the language chosen.
const words = {
  es: {
    or: 'o', open: 'abierta', crossed: 'cruzada', turn: 'girar', move: 'mover',
    'a driver': 'un accionamiento', 'a body': 'un cuerpo', 'a point': 'un punto', 'a force': 'una fuerza', 'a torque': 'un par',
    'a spring': 'un muelle', 'a slider': 'una deslizadera', 'a slot': 'una ranura', 'the sweep': 'el barrido', units: 'units',
  },
};

// The Grashof classes of /api/check's loops (the core's stable names).
const grashof = {
  es: {
    'crank-rocker': 'manivela-balancín', 'rocker-crank': 'balancín-manivela', 'double-crank': 'doble manivela',
    'double-rocker': 'doble balancín', 'triple-rocker': 'triple balancín', 'change point': 'punto de cambio',
  },
};

const escape = (s) => s.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
const compiled = messages.map(([code, en, es]) => {
  const kinds = {};
  let source = '';
  let last = 0;
  for (const m of en.matchAll(/\{(\w+)(?::(\w+))?\}/g)) {
    source += escape(en.slice(last, m.index)) + `(?<${m[1]}>.+?)`;
    kinds[m[1]] = m[2] ?? '';
    last = m.index + m[0].length;
  }
  source += escape(en.slice(last));
  return { code, kinds, pattern: new RegExp(`^${source}$`, 's'), es };
});

// The stable code and parameters of a core message, or null when no template matches.
export function parseCoreMessage(text) {
  for (const { code, kinds, pattern, es } of compiled) {
    const m = pattern.exec(text);
    if (m) return { code, params: { ...m.groups }, kinds, templates: { es } };
  }
  return null;
}

// The message in language `lang` (the app's by default): the catalogue's template with the
// parameters put back, or the core's English when it has none.
export function coreText(text, lang = getLang()) {
  if (lang === 'en' || typeof text !== 'string') return text;
  const parsed = parseCoreMessage(text);
  const template = parsed?.templates[lang];
  if (!template) return text;
  return template.replace(/\{(\w+)\}/g, (_, name) => {
    const value = parsed.params[name] ?? '';
    if (parsed.kinds[name] === 'msg') return coreText(value, lang);
    if (parsed.kinds[name] === 'word') return words[lang]?.[value] ?? value;
    if (parsed.kinds[name] === 'list') return value.replace(/ or (?=[^ ]+$)/, ` ${words[lang]?.or ?? 'or'} `);
    return value;
  });
}

// True when the message has a translation in `lang` (the catalogue's test asks it of each
// message a student commonly meets).
export function hasTranslation(text, lang) {
  const parsed = parseCoreMessage(text);
  if (!parsed?.templates[lang]) return false;
  return Object.entries(parsed.kinds).every(([name, kind]) => (kind === 'msg' ? hasTranslation(parsed.params[name], lang)
    : kind === 'word' ? Boolean(words[lang]?.[parsed.params[name]]) : kind === 'list' ? Boolean(words[lang]?.or) : true));
}

export function grashofName(name, lang = getLang()) { return grashof[lang]?.[name] ?? name; }
