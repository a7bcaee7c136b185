// Runs the golden scenes' WebAssembly module (targets/wasm) under Node: prints its report and
// exits 0 when every scene matches. Usage: node targets/wasm.mjs path/to/hibi_targets_wasm.wasm
import { readFileSync } from 'node:fs';

const decoder = new TextDecoder();
let memory;
const imports = {
  env: {
    hibi_print: (ptr, len) => process.stdout.write(decoder.decode(new Uint8Array(memory.buffer, ptr, len))),
  },
};
const { instance } = await WebAssembly.instantiate(readFileSync(process.argv[2]), imports);
memory = instance.exports.memory;
const differ = instance.exports.hibi_scenes_run();
process.exitCode = differ === 0 ? 0 : 1;
