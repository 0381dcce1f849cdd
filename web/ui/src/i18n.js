// The app's strings, English and Spanish. t(key, ...args) picks the current language.
const strings = {
  en: {
    // Names that screen readers say (aria-label): data-i18n-aria in the page.
    ariaLanguage: 'Language', ariaLink: 'Link', ariaDrawing: 'Drawing', ariaSample: 'Sample',
    ariaStressMap: 'Stress map', play: 'Play', pause: 'Pause',
    law: 'Law', stiffness: 'Stiffness', freeLength: 'Free length',
    noModel: 'No model', share: 'Share', shareTitle: 'Copy a link holding this model',
    gallery: 'Gallery', editor: 'Editor', synthesis: 'Synthesis', downloads: 'Downloads',
    plot: 'Plot', table: 'Table', column: 'Column', run: 'Run',
    synthHint: 'Five-point path synthesis: every four-bar whose coupler point passes through five points, with both fixed pivots given.',
    dlCsv: 'Table (CSV)', dlModel: 'Model (YAML)', dlSvg: 'Drawing (SVG)', dlPng: 'Drawing (PNG)',
    dlGif: 'Animation (GIF)', dlReport: 'Report (HTML)',
    dlPlatesDxf: 'Plates for cutting (DXF)', dlPlatesSvg: 'Plates for cutting (SVG)',
    loading: 'Loading…', analysing: 'Analysing…', ok: 'OK', dof: (n) => `${n} DOF`,
    samples: (n) => `${n} samples`, incomplete: (why) => `stopped: ${why}`,
    noErrors: 'No errors.', errorAt: (l, c) => `line ${l}, column ${c}: `,
    running: 'Running…', designsFound: (n, s) => `${n} design${n === 1 ? '' : 's'} (${s} solution${s === 1 ? '' : 's'})`,
    open: 'Open', defectFree: 'defect-free', defects: 'defects', complex: 'complex',
    minMu: 'min. transmission', maxErr: 'max. error', copied: 'Link copied',
    nothing: 'Open a model from the gallery, or type one in the editor.',
    design: (r, name) => `Design ${r} of “${name}”`, failed: 'Failed',
    noDrag: (p) => `${p} is not written as [x, y]: edit it in the editor`,
    // The model editing tools, tables and body panel (canvas-tools.js, tables.js).
    model: 'Model', editFailed: (m) => `Cannot edit: ${m}`,
    toolSelect: 'Select, drag a point, pan', toolPoint: 'Add a point', toolLink: 'Add a link between two points',
    toolGround: 'Add a ground pivot, or toggle a point on the ground', toolSnap: 'Snap to the grid',
    undo: 'Undo (Ctrl+Z)', redo: 'Redo (Ctrl+Shift+Z)', zoomIn: 'Zoom in', zoomOut: 'Zoom out', fit: 'Fit the drawing',
    points: 'Points', name: 'Name', ground: 'Ground', groundOf: (p) => `${p} on the ground`, none: 'None',
    bodies: 'Bodies', bodyPoints: 'Points', length: 'Length', joints: 'Joints', joint: 'Joint', point: 'Point',
    along: 'Along', slider: 'slider', slot: 'slot', drivers: 'Drivers', driver: 'Driver', from: 'From', to: 'To',
    speed: 'Speed', atLimits: 'At limits (stop, reverse)', loads: 'Loads', load: 'Load', value1: 'Value', value2: 'Value', force: 'force at', torque: 'torque on',
    spring: 'spring', noLoads: 'No forces, torques or springs: add a force or a torque below, springs in the YAML.',
    bodyTitle: (b) => `Body ${b}`, close: 'Close', form: 'Form', formNone: 'none (massless line)', formBar: 'bar',
    formShape: 'shape (plate outline)', barWidth: 'Bar width', barMargin: 'Bar margin', barHole: 'Hole radius',
    shapeInYaml: 'The outline starts as a rectangle around the points: edit it, and add holes, in the YAML.', thickness: 'Thickness',
    deleteBody: 'Delete this body', material: 'Material', mass: 'Mass (kg)', inertia: 'Inertia (kg m²)',
    fixYamlFirst: 'The YAML cannot be read: fix it in the editor first.',
    modelHint: 'Edit a number and press Enter; tap a body in the drawing (or its name) to edit its properties.',
    retry: 'Retry', notUpdated: (why) => `Not updated: ${why}`,
    copyLink: 'Copy this link:', copyByHand: 'The link could not be copied here: copy it from the box under the header.',
  },
  es: {
    ariaLanguage: 'Idioma', ariaLink: 'Enlace', ariaDrawing: 'Dibujo', ariaSample: 'Muestra',
    ariaStressMap: 'Mapa de tensiones', play: 'Reproducir', pause: 'Pausa',
    law: 'Ley', stiffness: 'Rigidez', freeLength: 'Longitud libre',
    noModel: 'Sin modelo', share: 'Compartir', shareTitle: 'Copiar un enlace con este modelo',
    gallery: 'Galería', editor: 'Editor', synthesis: 'Síntesis', downloads: 'Descargas',
    plot: 'Gráfica', table: 'Tabla', column: 'Columna', run: 'Calcular',
    synthHint: 'Síntesis de trayectoria por cinco puntos: todos los cuadriláteros cuyo punto del acoplador pasa por cinco puntos, con los dos pivotes fijos dados.',
    dlCsv: 'Tabla (CSV)', dlModel: 'Modelo (YAML)', dlSvg: 'Dibujo (SVG)', dlPng: 'Dibujo (PNG)',
    dlGif: 'Animación (GIF)', dlReport: 'Informe (HTML)',
    dlPlatesDxf: 'Placas para corte (DXF)', dlPlatesSvg: 'Placas para corte (SVG)',
    loading: 'Cargando…', analysing: 'Analizando…', ok: 'OK', dof: (n) => `${n} GDL`,
    samples: (n) => `${n} muestras`, incomplete: (why) => `detenido: ${why}`,
    noErrors: 'Sin errores.', errorAt: (l, c) => `línea ${l}, columna ${c}: `,
    running: 'Calculando…', designsFound: (n, s) => `${n} diseño${n === 1 ? '' : 's'} (${s} ${s === 1 ? 'solución' : 'soluciones'})`,
    open: 'Abrir', defectFree: 'sin defectos', defects: 'defectos', complex: 'complejo',
    minMu: 'transmisión mín.', maxErr: 'error máx.', copied: 'Enlace copiado',
    nothing: 'Abra un modelo de la galería o escriba uno en el editor.',
    design: (r, name) => `Diseño ${r} de «${name}»`, failed: 'Error',
    noDrag: (p) => `${p} no está escrito como [x, y]: edítelo en el editor`,
    model: 'Modelo', editFailed: (m) => `No se puede editar: ${m}`,
    toolSelect: 'Seleccionar, arrastrar un punto, desplazar', toolPoint: 'Añadir un punto', toolLink: 'Añadir una barra entre dos puntos',
    toolGround: 'Añadir un pivote fijo, o fijar/soltar un punto', toolSnap: 'Ajustar a la rejilla',
    undo: 'Deshacer (Ctrl+Z)', redo: 'Rehacer (Ctrl+Mayús+Z)', zoomIn: 'Acercar', zoomOut: 'Alejar', fit: 'Encuadrar el dibujo',
    points: 'Puntos', name: 'Nombre', ground: 'Fijo', groundOf: (p) => `${p} fijo al bastidor`, none: 'Ninguno',
    bodies: 'Cuerpos', bodyPoints: 'Puntos', length: 'Longitud', joints: 'Pares', joint: 'Par', point: 'Punto',
    along: 'A lo largo de', slider: 'deslizadera', slot: 'ranura', drivers: 'Accionamientos', driver: 'Accionamiento', from: 'Desde', to: 'Hasta',
    speed: 'Velocidad', atLimits: 'En los límites (stop, reverse)', loads: 'Cargas', load: 'Carga', value1: 'Valor', value2: 'Valor', force: 'fuerza en', torque: 'par sobre',
    spring: 'muelle', noLoads: 'Sin fuerzas, pares ni muelles: añada una fuerza o un par abajo, los muelles en el YAML.',
    bodyTitle: (b) => `Cuerpo ${b}`, close: 'Cerrar', form: 'Forma', formNone: 'ninguna (línea sin masa)', formBar: 'barra',
    formShape: 'forma (contorno de placa)', barWidth: 'Ancho de barra', barMargin: 'Margen de barra', barHole: 'Radio del agujero',
    shapeInYaml: 'El contorno empieza como un rectángulo alrededor de los puntos: edítelo, y añada agujeros, en el YAML.', thickness: 'Espesor',
    deleteBody: 'Eliminar este cuerpo', material: 'Material', mass: 'Masa (kg)', inertia: 'Inercia (kg m²)',
    fixYamlFirst: 'El YAML no se puede leer: corríjalo antes en el editor.',
    modelHint: 'Edite un número y pulse Intro; toque un cuerpo en el dibujo (o su nombre) para editar sus propiedades.',
    retry: 'Reintentar', notUpdated: (why) => `Sin actualizar: ${why}`,
    copyLink: 'Copie este enlace:', copyByHand: 'Aquí no se pudo copiar el enlace: cópielo del recuadro bajo la cabecera.',
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
  // What is written from data (the overlays' legend, the synthesis status) is written again.
  document.dispatchEvent(new Event('nbar:lang'));
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
  for (const el of document.querySelectorAll('[data-i18n-aria]')) el.setAttribute('aria-label', t(el.dataset.i18nAria));
}
