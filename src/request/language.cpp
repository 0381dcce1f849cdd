// The catalogue of the core's messages in other languages (include/nbar/request/language.hpp):
// each message by its English template, said again per language. The web app used to carry this
// catalogue itself and translate the API's English in the browser; here every front-end that
// takes a language gets the same words, and a template is written once.
#include "nbar/request/language.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include "nbar/request/options.hpp"

namespace nbar::request {

namespace {

// clang-format off
const std::vector<MessageTemplate> kCatalogue = {
    // Model errors (invalid_model), the ones a student meets first; then assembly
    // (cannot_assemble), the constraints' labels (explain's equations, the assembly's errors),
    // the sweep's stop and warnings, the check's joints and the Newton start.
    {"unknown_point",
     "unknown point '{name}' (points are: {names})",
     "punto desconocido '{name}' (los puntos son: {names})"},
    {"model_without_points",
     "the model has no points",
     "el modelo no tiene puntos"},
    {"points_empty",
     "`points` is empty: a model needs at least one point",
     "`points` está vacío: un modelo necesita al menos un punto"},
    {"unknown_key_top",
     "unknown key '{key}' at the top level; did you mean '{hint}'?",
     "clave desconocida '{key}' en el nivel superior; ¿quería decir '{hint}'?"},
    {"unknown_key_top_plain",
     "unknown key '{key}' at the top level (allowed: {keys})",
     "clave desconocida '{key}' en el nivel superior (se admiten: {keys})"},
    {"unknown_key_in_hint",
     "unknown key '{key}' in {where:word}; did you mean '{hint}'?",
     "clave desconocida '{key}' en {where}; ¿quería decir '{hint}'?"},
    {"unknown_key_in",
     "unknown key '{key}' in {where:word} (allowed: {keys})",
     "clave desconocida '{key}' en {where} (se admiten: {keys})"},
    {"unknown_body_hint",
     "unknown body '{name}'; did you mean '{hint}'?",
     "cuerpo desconocido '{name}'; ¿quería decir '{hint}'?"},
    {"unknown_body",
     "unknown body '{name}' (bodies are: {names})",
     "cuerpo desconocido '{name}' (los cuerpos son: {names})"},
    {"unknown_length_unit",
     "unknown length unit '{unit}' (use {units:list})",
     "unidad de longitud desconocida '{unit}' (use {units})"},
    {"unknown_angle_unit",
     "unknown angle unit '{unit}' (use {units:list})",
     "unidad de ángulo desconocida '{unit}' (use {units})"},
    {"needs_speed_unit",
     "'{value}' needs a unit per time such as {units:list}",
     "'{value}' necesita una unidad por tiempo, como {units}"},
    {"not_a_number",
     "{what} must be a number, not {value}",
     "{what} debe ser un número, no {value}"},
    {"defined_twice",
     "point '{name}' is defined twice (first given on line {line})",
     "el punto '{name}' está definido dos veces (la primera en la línea {line})"},
    {"lengths_two_points",
     "body '{name}' has {n} points: `lengths` applies only to bodies with two points",
     "el cuerpo '{name}' tiene {n} puntos: `lengths` solo se aplica a cuerpos de dos puntos"},
    {"driver_count",
     "the mechanism has {dof} degree of freedom (Gruebler-Kutzbach count: {count}) but {drivers} drivers are given; {why:msg}",
     "el mecanismo tiene {dof} grado de libertad (recuento de Grübler-Kutzbach: {count}) pero se dan {drivers} accionamientos; {why}"},
    {"driver_count_plural",
     "the mechanism has {dof} degrees of freedom (Gruebler-Kutzbach count: {count}) but {drivers} drivers are given; {why:msg}",
     "el mecanismo tiene {dof} grados de libertad (recuento de Grübler-Kutzbach: {count}) pero se dan {drivers} accionamientos; {why}"},
    {"driver_count_plural_one",
     "the mechanism has {dof} degrees of freedom (Gruebler-Kutzbach count: {count}) but {drivers} driver is given; {why:msg}",
     "el mecanismo tiene {dof} grados de libertad (recuento de Grübler-Kutzbach: {count}) pero se da {drivers} accionamiento; {why}"},
    {"yaml_unclosed",
     "invalid YAML: this '{open}' is never closed by a '{close}' ({detail})",
     "YAML no válido: este '{open}' no se cierra nunca con un '{close}'"},
    {"yaml_tab",
     "invalid YAML: tab characters are not allowed in YAML indentation; indent with spaces",
     "YAML no válido: no se admiten tabuladores en la sangría del YAML; sangre con espacios"},
    // Why the drivers do not match the degrees of freedom.
    {"add_driver",
     "add one driver per free input",
     "añada un accionamiento por cada entrada libre"},
    {"body_still_moves",
     "body '{body}' can still move with the drivers held ({joints}): give it a joint, a slider or a driver, or add one driver per free input",
     "el cuerpo '{body}' aún puede moverse con los accionamientos fijos ({joints}): dele una junta, una deslizadera o un accionamiento, o añada un accionamiento por cada entrada libre"},
    {"driver_too_many",
     "driver '{name}' moves what the joints and the drivers before it already fix: remove it",
     "el accionamiento '{name}' mueve lo que las juntas y los accionamientos anteriores ya fijan: quítelo"},
    {"yaml",
     "invalid YAML: {detail}",
     "YAML no válido: {detail}"},
    {"cannot_assemble",
     "cannot assemble the drawn pose with the given lengths: {reason:msg}",
     "no se puede montar la posición dibujada con las longitudes dadas: {reason}"},
    {"constraint_unmet",
     "constraint '{constraint:msg}' cannot be met (off by {off})",
     "la restricción «{constraint}» no se puede cumplir (con un error de {off})"},
    {"length_of",
     "length of {body} ({points})",
     "longitud de {body} ({points})"},
    {"shape_of",
     "shape of {body} ({point}, {axis})",
     "forma de {body} ({point}, {axis})"},
    {"on_line",
     "{point} of {body} on the line {line}",
     "{point} de {body} sobre la recta {line}"},
    {"orientation_of",
     "orientation of {body} along {line}",
     "orientación de {body} a lo largo de {line}"},
    {"in_slot",
     "{point} in the slot {line}",
     "{point} en la ranura {line}"},
    {"driver_row",
     "driver {name}",
     "accionamiento {name}"},
    // The start not reached: each driver's stop, then why ("; " between the parts).
    {"cannot_reach",
     "cannot reach the drivers' starting values from the drawn pose on its branch; {rest:msg}",
     "no se alcanzan los valores iniciales de los accionamientos desde la posición dibujada en su rama; {rest}"},
    {"driver_stops_either_way",
     "driver '{name}' stops at {at} (drawn {drawn}, wanted {wanted}) either way round; {rest:msg}",
     "el accionamiento '{name}' se detiene en {at} (dibujado {drawn}, pedido {wanted}) en ambos sentidos; {rest}"},
    {"driver_stops",
     "driver '{name}' stops at {at} (drawn {drawn}, wanted {wanted}); {rest:msg}",
     "el accionamiento '{name}' se detiene en {at} (dibujado {drawn}, pedido {wanted}); {rest}"},
    {"other_branch",
     "the wanted values can only be assembled on another branch: draw the mechanism on that branch",
     "los valores pedidos solo se pueden montar en otra rama: dibuje el mecanismo en esa rama"},
    {"wanted_unmet",
     "at the wanted values constraint '{constraint:msg}' cannot be met (the closest pose found leaves it off by {off})",
     "con los valores pedidos la restricción «{constraint}» no se puede cumplir (la posición más cercana hallada la deja con un error de {off})"},
    {"sweep_stopped",
     "sweep stopped between steps {a} and {b} at {at}: {why:msg}",
     "barrido detenido entre los pasos {a} y {b} en {at}: {why}"},
    // The simulation's stop at --max-steps (forward_dynamics.cpp), and the command line's line
    // that says a simulation stopped early (apps/nbar/simulation_run.hpp) around any stop.
    {"simulation_max_steps",
     "the simulation took more than {steps} steps before {end} (stopped at {at})",
     "la simulación dio más de {steps} pasos antes de {end} (se detuvo en {at})"},
    {"simulation_stopped_early",
     "the simulation stopped early: {reason:msg}",
     "la simulación se detuvo antes de tiempo: {reason}"},
    // What the command line adds after a sweep's stop reason (apps/nbar/common.hpp, finish).
    {"sweep_rows_written",
     "({rows} rows written)",
     "({rows} filas escritas)"},
    {"singular_position",
     "the constraints cannot be followed past this point: a singular position, either a limit (toggle) that the input cannot pass or a change point where two branches cross (reciprocal condition of the Jacobian {rcond})",
     "las restricciones no se pueden seguir más allá de este punto: una posición singular, o bien un límite (agarrotamiento) que la entrada no puede pasar, o bien un punto de cambio donde se cruzan dos ramas (condición recíproca del jacobiano {rcond})"},
    {"no_kinetics",
     "the model has no masses or loads (no `mass`, material, gravity, forces, torques or springs): every joint force and driver effort is zero",
     "el modelo no tiene masas ni cargas (ni `mass`, material, gravedad, fuerzas, pares o muelles): todas las fuerzas en las juntas y los esfuerzos de los accionamientos son nulos"},
    {"forces_not_unique",
     "the mechanism has redundant constraints: its joint forces are not unique (statically indeterminate); the minimum-norm set is given",
     "el mecanismo tiene restricciones redundantes: sus fuerzas en las juntas no son únicas (hiperestático); se da el conjunto de norma mínima"},
    {"branch_changed",
     "four-bar loop {loop} changed branch {where:msg} (now {branch:word})",
     "el lazo de cuatro barras {loop} cambió de rama {where} (ahora {branch})"},
    {"between_steps",
     "between steps {a} and {b}",
     "entre los pasos {a} y {b}"},
    {"change_point_passed",
     "passed a singular (change-point) position {where:msg} near {at}: the assembly branch may have changed there",
     "pasó por una posición singular (punto de cambio) {where} cerca de {at}: la rama de montaje puede haber cambiado ahí"},
    {"change_point_rocking",
     "the rocking path passes a singular (change-point) position at {at} ({involved}): the assembly branch may change there",
     "el camino oscilante pasa por una posición singular (punto de cambio) en {at} ({involved}): la rama de montaje puede cambiar ahí"},
    {"input_limited",
     "the sweep asks {driver} to {verb:word} {amount}, from {from} to {to}, but {who} lets it {verb2:word} {range} (limit positions): the sweep will stop at {stop}: {involved}",
     "el barrido pide a {driver} {verb} {amount}, de {from} a {to}, pero {who} le deja {verb2} {range} (posiciones límite): el barrido se detendrá en {stop}: {involved}"},
    {"many_turns",
     "the sweep turns {driver} {turns} times, from {from} to {to}{hint}",
     "el barrido gira {driver} {turns} veces, de {from} a {to}{hint}"},
    {"revolute",
     "revolute {point} ({bodies})",
     "par de rotación {point} ({bodies})"},
    {"start_drawn",
     "the drawn pose",
     "la posición dibujada"},
    {"start_step",
     "step {step}'s pose",
     "la posición del paso {step}"},
    // A simulation's event where its stop condition is met (forward_dynamics.cpp): /api/simulate's
    // `events`, which the web app's status says in Simulate mode.
    {"simulation_stop_condition",
     "the stop condition '{condition}' was met at t = {time} s",
     "la condición de parada '{condition}' se cumplió en t = {time} s"},
    // The Grashof classes of the check's loops and of synthesis designs (the core's names).
    {"grashof_crank_rocker", "crank-rocker", "manivela-balancín"},
    {"grashof_rocker_crank", "rocker-crank", "balancín-manivela"},
    {"grashof_double_crank", "double-crank", "doble manivela"},
    {"grashof_double_rocker", "double-rocker", "doble balancín"},
    {"grashof_triple_rocker", "triple-rocker", "triple balancín"},
    {"grashof_change_point", "change point", "punto de cambio"},
    // The check's descriptions: a four-bar loop's Grashof facts (describe in loops.cpp; each
    // length "name value", the last with the unit), its rocker's swing, a slider-crank's and a
    // quick-return's strokes (summary_facts.cpp). A crank-rocker whose output is the crank keeps
    // the class "crank-rocker" here: the description names the class as to_string does.
    {"loop_one_crank",
     "{kind:msg}: frame {frame}, input {input}, coupler {coupler}, output {output}; (p + q) - (s + l) = {margin}; turns fully relative to {ground}: {crank}",
     "{kind}: bastidor {frame}, entrada {input}, biela {coupler}, salida {output}; (p + q) - (s + l) = {margin}; gira completamente respecto a {ground}: {crank}"},
    {"loop_two_cranks",
     "{kind:msg}: frame {frame}, input {input}, coupler {coupler}, output {output}; (p + q) - (s + l) = {margin}; turns fully relative to {ground}: {crank} and {other}",
     "{kind}: bastidor {frame}, entrada {input}, biela {coupler}, salida {output}; (p + q) - (s + l) = {margin}; giran completamente respecto a {ground}: {crank} y {other}"},
    {"loop_change_point_one",
     "change point: frame {frame}, input {input}, coupler {coupler}, output {output}; (p + q) - (s + l) = {margin}; turns fully relative to {ground}: {crank} (through change points)",
     "punto de cambio: bastidor {frame}, entrada {input}, biela {coupler}, salida {output}; (p + q) - (s + l) = {margin}; gira completamente respecto a {ground}: {crank} (pasando por puntos de cambio)"},
    {"loop_change_point_two",
     "change point: frame {frame}, input {input}, coupler {coupler}, output {output}; (p + q) - (s + l) = {margin}; turns fully relative to {ground}: {crank} and {other} (through change points)",
     "punto de cambio: bastidor {frame}, entrada {input}, biela {coupler}, salida {output}; (p + q) - (s + l) = {margin}; giran completamente respecto a {ground}: {crank} y {other} (pasando por puntos de cambio)"},
    {"loop_change_point_none",
     "change point: frame {frame}, input {input}, coupler {coupler}, output {output}; (p + q) - (s + l) = {margin}; no link turns fully",
     "punto de cambio: bastidor {frame}, entrada {input}, biela {coupler}, salida {output}; (p + q) - (s + l) = {margin}; ningún eslabón gira completamente"},
    {"loop_double_rocker",
     "double-rocker (Grashof): frame {frame}, input {input}, coupler {coupler}, output {output}; (p + q) - (s + l) = {margin}; the coupler turns fully, neither {input_name} nor {output_name} does",
     "doble balancín (Grashof): bastidor {frame}, entrada {input}, biela {coupler}, salida {output}; (p + q) - (s + l) = {margin}; la biela gira completamente; ni {input_name} ni {output_name} lo hacen"},
    {"loop_triple_rocker",
     "triple-rocker (non-Grashof): frame {frame}, input {input}, coupler {coupler}, output {output}; (p + q) - (s + l) = {margin}; no link turns fully",
     "triple balancín (no Grashof): bastidor {frame}, entrada {input}, biela {coupler}, salida {output}; (p + q) - (s + l) = {margin}; ningún eslabón gira completamente"},
    {"rocker_swing",
     "the rocker {rocker} swings {swing}, between {stretched} (crank and coupler stretched in line, {driver} at {crank_stretched}) and {folded} (folded, at {crank_folded}); the crank turns {to_stretched} from folded to stretched and {to_folded} back: time ratio {ratio}",
     "el balancín {rocker} oscila {swing}, entre {stretched} (manivela y biela extendidas en línea, {driver} en {crank_stretched}) y {folded} (plegadas, en {crank_folded}); la manivela gira {to_stretched} de plegada a extendida y {to_folded} de vuelta: relación de tiempos {ratio}"},
    {"slider_crank",
     "slider-crank {names}: crank {crank}, rod {rod}, offset {offset}; stroke {stroke}; dead centres at {driver} {outer} (outer) and {inner} (inner); the outstroke takes {outstroke} of crank turn, the return {return}: time ratio {ratio}",
     "biela-manivela {names}: manivela {crank}, biela {rod}, descentramiento {offset}; carrera {stroke}; puntos muertos con {driver} en {outer} (exterior) y {inner} (interior); la carrera de ida ocupa {outstroke} de giro de la manivela, la de retorno {return}: relación de tiempos {ratio}"},
    {"slider_crank_locked",
     "slider-crank {names}: crank {crank}, rod {rod}, offset {offset}: the crank cannot turn fully (rod - crank is not longer than the offset)",
     "biela-manivela {names}: manivela {crank}, biela {rod}, descentramiento {offset}: la manivela no puede dar la vuelta completa (biela - manivela no es mayor que el descentramiento)"},
    {"quick_return",
     "quick-return {names}: crank {crank}, pivots {distance} apart; the arm swings {swing}; its limits at {driver} {from} and {to}; one stroke takes {slow} of crank turn, the other {fast}: time ratio {ratio}",
     "retorno rápido {names}: manivela {crank}, pivotes a {distance} de distancia; el brazo oscila {swing}; sus posiciones extremas con {driver} en {from} y {to}; una carrera ocupa {slow} de giro de la manivela, la otra {fast}: relación de tiempos {ratio}"},
    {"quick_return_whitworth",
     "quick-return {names}: crank {crank} >= pivot distance {distance}: the arm turns fully (Whitworth)",
     "retorno rápido {names}: manivela {crank} >= distancia entre pivotes {distance}: el brazo da la vuelta completa (Whitworth)"},
};

// Words the core puts inside its messages ({name:word}), in Spanish.
const std::map<std::string_view, std::string_view> kSpanishWords = {
    {"open", "abierta"}, {"crossed", "cruzada"}, {"turn", "girar"}, {"move", "mover"},
    {"a driver", "un accionamiento"}, {"a body", "un cuerpo"}, {"a point", "un punto"},
    {"a force", "una fuerza"}, {"a torque", "un par"}, {"a spring", "un muelle"},
    {"a slider", "una deslizadera"}, {"a slot", "una ranura"}, {"the sweep", "el barrido"},
    {"units", "units"},
};
// clang-format on

// A template cut into its literal texts and its parameters, in order.
struct Part {
  std::string_view literal;  // a literal text, or empty for a parameter
  std::string_view name, kind;
  bool parameter = false;
};

std::vector<Part> parts_of(std::string_view text) {
  std::vector<Part> parts;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t open = text.find('{', at);
    const std::size_t close = open == std::string_view::npos ? open : text.find('}', open);
    if (close == std::string_view::npos) {
      parts.push_back({text.substr(at), {}, {}, false});
      break;
    }
    if (open > at) parts.push_back({text.substr(at, open - at), {}, {}, false});
    const std::string_view inside = text.substr(open + 1, close - open - 1);
    const std::size_t colon = inside.find(':');
    parts.push_back(
        {{}, inside.substr(0, colon), colon == std::string_view::npos ? "" : inside.substr(colon + 1), true});
    at = close + 1;
  }
  return parts;
}

struct Compiled {
  const MessageTemplate* entry;
  std::vector<Part> english;
};

const std::vector<Compiled>& compiled() {
  static const std::vector<Compiled> all = [] {
    std::vector<Compiled> out;
    for (const MessageTemplate& t : kCatalogue) out.push_back({&t, parts_of(t.english)});
    return out;
  }();
  return all;
}

using Values = std::map<std::string_view, std::string_view>;

// Whether text[at..] matches parts[k..], each parameter taking the shortest non-empty text
// after which the rest still matches (as a lazy regular expression would).
bool match_from(const std::vector<Part>& parts, std::size_t k, std::string_view text, std::size_t at, Values& values) {
  if (k == parts.size()) return at == text.size();
  const Part& part = parts[k];
  if (!part.parameter)
    return text.substr(at).starts_with(part.literal) &&
           match_from(parts, k + 1, text, at + part.literal.size(), values);
  if (k + 1 == parts.size()) {
    if (at >= text.size()) return false;
    values[part.name] = text.substr(at);
    return true;
  }
  const std::string_view next = parts[k + 1].literal;  // a literal always follows a parameter
  for (std::size_t end = text.find(next, at + 1); end != std::string_view::npos; end = text.find(next, end + 1)) {
    values[part.name] = text.substr(at, end - at);
    if (match_from(parts, k + 1, text, end, values)) return true;
  }
  return false;
}

std::size_t literal_size(const std::vector<Part>& parts) {
  std::size_t n = 0;
  for (const Part& p : parts) n += p.literal.size();
  return n;
}

// The template that matches the message with the most of its own words: a short general one
// ("driver {name}") never takes a message a longer one says ("driver '{name}' stops at ...").
const Compiled* matching(std::string_view message, Values& values) {
  const Compiled* best = nullptr;
  Values found;
  for (const Compiled& c : compiled()) {
    found.clear();
    if (match_from(c.english, 0, message, 0, found) &&
        (!best || literal_size(c.english) > literal_size(best->english))) {
      best = &c;
      values = found;
    }
  }
  return best;
}

std::string word_in(std::string_view word, Language language) {
  if (language == Language::Spanish)
    if (const auto it = kSpanishWords.find(word); it != kSpanishWords.end()) return std::string(it->second);
  return std::string(word);
}

// "A, B or C" with its last " or " said in the language.
std::string list_in(std::string_view list, Language language) {
  std::string out(list);
  const std::size_t last = out.rfind(" or ");
  if (language == Language::Spanish && last != std::string::npos && out.find(' ', last + 4) == std::string::npos)
    out.replace(last, 4, " o ");
  return out;
}

std::string_view template_in(const MessageTemplate& t, Language language) {
  return language == Language::Spanish ? t.spanish : t.english;
}

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

std::string trimmed(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return std::string(text.substr(first, text.find_last_not_of(" \t") - first + 1));
}

std::optional<Language> known_language(std::string_view code) {
  const std::string base = lower(trimmed(code.substr(0, code.find_first_of("-_"))));
  if (base == "en") return Language::English;
  if (base == "es") return Language::Spanish;
  return std::nullopt;
}

}  // namespace

const std::vector<MessageTemplate>& message_catalogue() { return kCatalogue; }

Language read_language(std::string_view code) {
  if (const std::optional<Language> language = known_language(code)) return *language;
  throw OptionError("lang", "the language '" + std::string(code) + "' is not one nbar speaks: use en or es");
}

Language accept_language(std::string_view header) {
  std::size_t at = 0;
  while (at <= header.size()) {
    const std::size_t comma = std::min(header.find(',', at), header.size());
    const std::string_view item = header.substr(at, comma - at);
    if (const std::optional<Language> language = known_language(item.substr(0, item.find(';')))) return *language;
    at = comma + 1;
  }
  return Language::English;
}

std::string language_code(Language language) { return language == Language::Spanish ? "es" : "en"; }

std::string translate(std::string_view message, Language language) {
  if (language == Language::English) return std::string(message);
  Values values;
  const Compiled* c = matching(message, values);
  if (!c) return std::string(message);
  std::string out;
  for (const Part& part : parts_of(template_in(*c->entry, language))) {
    if (!part.parameter) {
      out += part.literal;
      continue;
    }
    const std::string_view value = values[part.name];
    const auto kind = std::find_if(c->english.begin(), c->english.end(),
                                   [&](const Part& p) { return p.parameter && p.name == part.name; });
    const std::string_view how = kind == c->english.end() ? "" : kind->kind;
    out += how == "msg"    ? translate(value, language)
           : how == "word" ? word_in(value, language)
           : how == "list" ? list_in(value, language)
                           : std::string(value);
  }
  return out;
}

std::vector<std::string> message_codes(std::string_view message) {
  Values values;
  const Compiled* c = matching(message, values);
  if (!c) return {};
  std::vector<std::string> codes{std::string(c->entry->code)};
  for (const Part& part : c->english)
    if (part.parameter && part.kind == "msg")
      for (std::string& code : message_codes(values[part.name])) codes.push_back(std::move(code));
  return codes;
}

}  // namespace nbar::request
