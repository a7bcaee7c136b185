// The golden scenes in a module Worker (web/tests/page.html starts it).
import * as hibi from '../hibi.js';
import { runScenes } from './scenes.mjs';

try {
  await hibi.init();
  postMessage({ hashes: runScenes(hibi) });
} catch (e) {
  postMessage({ error: String((e && e.stack) || e) });
}
