// Compares two outputs of libm_compare.cpp (native and WebAssembly): for each function, how many
// of its results differ and by how many units in the last place at most.
//   node libm_compare.mjs native.txt wasm.txt
import { readFileSync } from 'node:fs';

const names = ['sin', 'cos', 'tan', 'atan2', 'asin', 'acos', 'atan', 'pow', 'exp', 'log', 'sqrt', 'hypot', 'cbrt', 'fmod'];
const [first, second] = process.argv.slice(2).map((file) => readFileSync(file, 'utf8').trim().split('\n'));
if (first.length !== second.length) throw new Error(`${first.length} lines against ${second.length}`);
const differ = names.map(() => 0);
const ulps = names.map(() => 0n);
for (let line = 0; line < first.length; ++line) {
  const [a, b] = [first[line].trim().split(' '), second[line].trim().split(' ')];
  for (let k = 0; k < names.length; ++k) {
    if (a[k] === b[k]) continue;
    differ[k] += 1;
    const ulp = BigInt(`0x${a[k]}`) - BigInt(`0x${b[k]}`);
    const size = ulp < 0n ? -ulp : ulp;
    if (size > ulps[k]) ulps[k] = size;
  }
}
for (let k = 0; k < names.length; ++k)
  console.log(`${names[k]}: ${differ[k]} of ${first.length} differ (${(100 * differ[k] / first.length).toFixed(2)} %), at most ${ulps[k]} ulp`);
