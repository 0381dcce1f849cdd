// The strings of the files (New from a template, Open, drop, JSON download) and of the Model
// tab's adding, renaming, deleting and refused numbers, in English and Spanish (added to i18n.js's lists).
import { addStrings } from './i18n.js';

addStrings({
  en: {
    newModel: 'New', openFile: 'Open…', dropHint: 'or drop a .yaml or .json file here', dlJson: 'Solve (JSON)',
    fileNotModel: (f) => `${f} is not a model file: open a .yaml, .yml or .json file`,
    fileTooLarge: (f, kb, max) => `${f} is too large (${kb} KiB): a model file is at most ${max} KiB`,
    fileNotText: (f) => `${f} is not text (UTF-8): open a .yaml, .yml or .json model file`,
    fileOneOnly: 'Several files dropped: the first is opened',
    nameOf: (p) => `Name of point ${p} (type a new name to rename it everywhere)`,
    deletePoint: (p) => `Delete point ${p}`, deleteRow: 'Delete this row', body: 'Body',
    addSlider: 'Add a slider', addDriver: 'Add a driver', addForce: 'Add a force', addTorque: 'Add a torque',
    numberOutOfRange: (v) => `${v} is beyond the range of a number (at most about 1.8e308 either way); the model is unchanged`,
  },
  es: {
    newModel: 'Nuevo', openFile: 'Abrir…', dropHint: 'o suelte aquí un archivo .yaml o .json', dlJson: 'Cálculo (JSON)',
    fileNotModel: (f) => `${f} no es un archivo de modelo: abra un archivo .yaml, .yml o .json`,
    fileTooLarge: (f, kb, max) => `${f} es demasiado grande (${kb} KiB): un modelo ocupa como mucho ${max} KiB`,
    fileNotText: (f) => `${f} no es texto (UTF-8): abra un modelo .yaml, .yml o .json`,
    fileOneOnly: 'Se soltaron varios archivos: se abre el primero',
    nameOf: (p) => `Nombre del punto ${p} (escriba otro nombre para renombrarlo en todo el modelo)`,
    deletePoint: (p) => `Eliminar el punto ${p}`, deleteRow: 'Eliminar esta fila', body: 'Cuerpo',
    addSlider: 'Añadir una deslizadera', addDriver: 'Añadir un accionamiento', addForce: 'Añadir una fuerza', addTorque: 'Añadir un par',
    numberOutOfRange: (v) => `${v} está fuera del rango de los números (como mucho unos 1,8e308 en valor absoluto); el modelo no cambia`,
  },
});
