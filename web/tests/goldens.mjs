// The golden hashes of targets/scenes/src/lib.rs (GOLDENS), read from the source.
import { readFileSync } from 'node:fs';

export function goldens() {
  const source = readFileSync(new URL('../../targets/scenes/src/lib.rs', import.meta.url), 'utf8');
  const list = source.slice(source.indexOf('pub const GOLDENS'), source.indexOf('];', source.indexOf('pub const GOLDENS')));
  const map = {};
  for (const [, name, hash] of list.matchAll(/\("([^"]+)",\s*(\d+)\)/g)) map[name] = hash;
  return map;
}
