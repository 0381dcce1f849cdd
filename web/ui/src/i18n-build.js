// The strings of building a model from nothing (build-model.js: New → empty, the sketch of a
// model being built, the slider tool), in English and Spanish (added to i18n.js's lists).
import { addStrings } from './i18n.js';

addStrings({
  en: {
    newEmpty: 'Empty model', blankName: 'New model',
    blankComment: 'A new model: add points and links with the drawing tools, then a driver in the Model tab.',
    building: 'Building', buildDof: (n) => `${n} DOF`, buildGruebler: (n) => `${n} DOF (Gruebler-Kutzbach count)`,
    toolSlider: 'Add a slider: tap its point, then the direction of its guide',
    sliderTapPoint: 'Slider: tap the point that slides first',
    sliderTapAway: 'Slider: tap away from the point, in the direction of its guide',
    sliderRefused: (why) => `Cannot add this slider: ${why}`,
    newBlock: 'a new block', pivotOnTarget: (p, k) => `The pivot ${p} is at target point ${k}: a pivot on the path makes a degenerate design; move one of them`,
  },
  es: {
    newEmpty: 'Modelo vacío', blankName: 'Modelo nuevo',
    blankComment: 'Un modelo nuevo: añada puntos y barras con las herramientas del dibujo, y luego un accionamiento en la pestaña Modelo.',
    building: 'En construcción', buildDof: (n) => `${n} GDL`, buildGruebler: (n) => `${n} GDL (recuento de Grübler-Kutzbach)`,
    toolSlider: 'Añadir una deslizadera: toque su punto y luego la dirección de su guía',
    sliderTapPoint: 'Deslizadera: toque primero el punto que desliza',
    sliderTapAway: 'Deslizadera: toque lejos del punto, en la dirección de su guía',
    sliderRefused: (why) => `No se puede añadir esta deslizadera: ${why}`,
    newBlock: 'un bloque nuevo', pivotOnTarget: (p, k) => `El pivote ${p} está en el punto objetivo ${k}: un pivote sobre la trayectoria da un diseño degenerado; mueva uno de los dos`,
  },
});
