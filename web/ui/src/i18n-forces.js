// The strings of the plot's several curves, the per-link stress table, Explain's forces and
// stresses at the pose and its instant centres on the drawing, and the drag at the start pose,
// in English and Spanish (added to i18n.js's lists).
import { addStrings } from './i18n.js';

addStrings({
  en: {
    moreCurves: 'More curves', addCurve: '+ add a curve', removeCurve: (c) => `Take ${c} off the plot`,
    dragAtStart: (p) => `Points are edited at the start pose (sample 0): the drawing is back there; drag ${p} from where it is now.`,
    stTitle: 'Each link’s peak stress over the sweep', stLink: 'Link', stPeak: 'Peak von Mises', stStep: 'Step',
    stWhere: 'Where: x, y', stSafety: 'Safety factor', stNoYield: 'no yield strength',
    stGo: (b, k) => `Show ${b}’s peak: step ${k}`,
    stHint: 'Beam stresses (nbar stress). Safety factor: the material’s yield strength over the peak. Where: x from the link’s first point towards its second, y to its left. Tap a row to go to its step.',
    exForces: 'Forces at this pose', exForcesHint: 'The joint reactions (the force one link exerts on the other at the joint, as A.crank>coupler: the crank on the coupler) and the drivers’ efforts, from the inverse dynamics of the sweep (nbar solve --dynamics) at this sample.',
    exForcesNone: 'No inverse dynamics for this model.', exForceCol: 'Column', exValue: 'Value',
    exStresses: 'Stresses at this pose', exStressesHint: 'Each shaped link’s largest von Mises stress over its cross-sections at this sample (nbar stress --section-profile LINK --step K), and where along the link.',
    exStressesNone: 'No shaped links: no stresses.', exAt: 'at x', exCentresDrawn: 'Each instant centre is marked on the drawing with its pair of links (crank,coupler); those at infinity are not.',
  },
  es: {
    moreCurves: 'Más curvas', addCurve: '+ añadir una curva', removeCurve: (c) => `Quitar ${c} de la gráfica`,
    dragAtStart: (p) => `Los puntos se editan en la posición inicial (muestra 0): el dibujo ha vuelto a ella; arrastre ${p} desde donde está ahora.`,
    stTitle: 'Tensión máxima de cada eslabón en el barrido', stLink: 'Eslabón', stPeak: 'Von Mises máxima', stStep: 'Paso',
    stWhere: 'Dónde: x, y', stSafety: 'Coef. de seguridad', stNoYield: 'sin límite elástico',
    stGo: (b, k) => `Mostrar el máximo de ${b}: paso ${k}`,
    stHint: 'Tensiones de viga («nbar stress»). Coeficiente de seguridad: el límite elástico del material entre la máxima. Dónde: x desde el primer punto del eslabón hacia el segundo, y hacia su izquierda. Toque una fila para ir a su paso.',
    exForces: 'Fuerzas en esta posición', exForcesHint: 'Las reacciones en las juntas (la fuerza que un eslabón ejerce sobre el otro en la junta, como A.crank>coupler: la manivela sobre el acoplador) y los esfuerzos de los accionamientos, de la dinámica inversa del barrido (nbar solve --dynamics) en esta muestra.',
    exForcesNone: 'Este modelo no tiene dinámica inversa.', exForceCol: 'Columna', exValue: 'Valor',
    exStresses: 'Tensiones en esta posición', exStressesHint: 'La mayor tensión de von Mises de cada eslabón con forma entre sus secciones en esta muestra («nbar stress --section-profile ESLABÓN --step K»), y dónde a lo largo del eslabón.',
    exStressesNone: 'No hay eslabones con forma: no hay tensiones.', exAt: 'en x', exCentresDrawn: 'Cada centro instantáneo está marcado en el dibujo con su par de eslabones (crank,coupler); los del infinito no.',
  },
});
