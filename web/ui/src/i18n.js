// The app's strings, English and Spanish. t(key, ...args) picks the current language.
const strings = {
  en: {
    noModel: 'No model', share: 'Share', shareTitle: 'Copy a link holding this model',
    gallery: 'Gallery', editor: 'Editor', synthesis: 'Synthesis', downloads: 'Downloads',
    plot: 'Plot', table: 'Table', column: 'Column', run: 'Run',
    synthHint: 'Five-point path synthesis: every four-bar whose coupler point passes through five points, with both fixed pivots given.',
    dlCsv: 'Table (CSV)', dlModel: 'Model (YAML)', dlSvg: 'Drawing (SVG)', dlPng: 'Drawing (PNG)',
    dlGif: 'Animation (GIF)', dlReport: 'Report (HTML)',
    loading: 'Loading…', analysing: 'Analysing…', ok: 'OK', dof: (n) => `${n} DOF`,
    samples: (n) => `${n} samples`, incomplete: (why) => `stopped: ${why}`,
    noErrors: 'No errors.', errorAt: (l, c) => `line ${l}, column ${c}: `,
    running: 'Running…', designsFound: (n, s) => `${n} design${n === 1 ? '' : 's'} (${s} solutions)`,
    open: 'Open', defectFree: 'defect-free', defects: 'defects', complex: 'complex',
    minMu: 'min. transmission', maxErr: 'max. error', copied: 'Link copied',
    nothing: 'Open a model from the gallery, or type one in the editor.',
    design: (r, name) => `Design ${r} of “${name}”`, failed: 'Failed',
    noDrag: (p) => `${p} is not written as [x, y]: edit it in the editor`,
  },
  es: {
    noModel: 'Sin modelo', share: 'Compartir', shareTitle: 'Copiar un enlace con este modelo',
    gallery: 'Galería', editor: 'Editor', synthesis: 'Síntesis', downloads: 'Descargas',
    plot: 'Gráfica', table: 'Tabla', column: 'Columna', run: 'Calcular',
    synthHint: 'Síntesis de trayectoria por cinco puntos: todos los cuadriláteros cuyo punto del acoplador pasa por cinco puntos, con los dos pivotes fijos dados.',
    dlCsv: 'Tabla (CSV)', dlModel: 'Modelo (YAML)', dlSvg: 'Dibujo (SVG)', dlPng: 'Dibujo (PNG)',
    dlGif: 'Animación (GIF)', dlReport: 'Informe (HTML)',
    loading: 'Cargando…', analysing: 'Analizando…', ok: 'OK', dof: (n) => `${n} GDL`,
    samples: (n) => `${n} muestras`, incomplete: (why) => `detenido: ${why}`,
    noErrors: 'Sin errores.', errorAt: (l, c) => `línea ${l}, columna ${c}: `,
    running: 'Calculando…', designsFound: (n, s) => `${n} diseño${n === 1 ? '' : 's'} (${s} soluciones)`,
    open: 'Abrir', defectFree: 'sin defectos', defects: 'defectos', complex: 'complejo',
    minMu: 'transmisión mín.', maxErr: 'error máx.', copied: 'Enlace copiado',
    nothing: 'Abra un modelo de la galería o escriba uno en el editor.',
    design: (r, name) => `Diseño ${r} de «${name}»`, failed: 'Error',
    noDrag: (p) => `${p} no está escrito como [x, y]: edítelo en el editor`,
  },
};

// More strings from a module of their own (e.g. i18n-motion.js), so that parts of the app add
// theirs without editing the lists above.
export function addStrings(more) {
  for (const l of Object.keys(strings)) Object.assign(strings[l], more[l] ?? {});
}

let lang = 'en';
try { lang = localStorage.getItem('nbar.lang') || (navigator.language || 'en').slice(0, 2); } catch { /* private mode */ }
if (!strings[lang]) lang = 'en';

export function getLang() { return lang; }
export function setLang(l) {
  lang = strings[l] ? l : 'en';
  try { localStorage.setItem('nbar.lang', lang); } catch { /* private mode */ }
  translatePage();
}
export function t(key, ...args) {
  const s = strings[lang][key] ?? strings.en[key] ?? key;
  return typeof s === 'function' ? s(...args) : s;
}
export function translatePage() {
  document.documentElement.lang = lang;
  for (const el of document.querySelectorAll('[data-i18n]')) {
    if (el.id === 'model-name' && el.dataset.named) continue;
    el.textContent = t(el.dataset.i18n);
  }
  for (const el of document.querySelectorAll('[data-i18n-title]')) el.title = t(el.dataset.i18nTitle);
}
