// Scenario editor: a dialog to paste, upload, validate, save and start a
// scenario. Errors are shown in words and at the field their JSON path names
// (the server's `robot.links[3].length`), located in the text by a small
// tokenizer, since JSON.parse forgets where values were.
import { element } from './dom.js';

const MAX_UPLOAD_BYTES = 1024 * 1024;
const NAME_PATTERN = /^[A-Za-z0-9_.-]{1,64}$/;  // the server's rule for stored names

// ---- JSON text locator -----------------------------------------------------

class JsonSyntaxError extends Error {
  constructor(message, offset) { super(message); this.offset = offset; }
}

// Walks JSON text and records, for every value, where its key (if any) and the
// value itself start and end: Map(path → {keyStart, keyEnd, valueStart, valueEnd, container}).
// Paths are written like the server's: `robot.links[3].length`.
export function scanJson(text) {
  const spans = new Map();
  let i = 0;
  const fail = (message, at = i) => { throw new JsonSyntaxError(message, Math.min(at, text.length)); };
  const skipSpace = () => { while (i < text.length && ' \t\n\r'.includes(text[i])) ++i; };
  const describe = () => (i >= text.length ? 'the end of the text' : text[i] === '"' ? 'a string' : `“${text[i]}”`);
  const startsValue = () => /["\-0-9tfn[{]/.test(text[i] ?? '');

  function readString() {  // i at the opening quote; returns the decoded text
    const start = i++;
    let out = '';
    for (;;) {
      if (i >= text.length) fail('this string is never closed (missing ")', start);
      const c = text[i];
      if (c === '"') { ++i; return out; }
      if (c === '\\') {
        const e = text[i + 1];
        if (e === 'u') {
          const hex = text.slice(i + 2, i + 6);
          if (!/^[0-9a-fA-F]{4}$/.test(hex)) fail('\\u must be followed by four hex digits');
          out += String.fromCharCode(parseInt(hex, 16));
          i += 6;
        } else {
          const map = { '"': '"', '\\': '\\', '/': '/', b: '\b', f: '\f', n: '\n', r: '\r', t: '\t' };
          if (!(e in map)) fail(`unknown escape \\${e ?? ''} in a string`);
          out += map[e];
          i += 2;
        }
      } else if (c < ' ') {
        fail(c === '\n' ? 'a string may not span lines (missing " before the line end?)' : 'control character inside a string');
      } else {
        out += c;
        ++i;
      }
    }
  }

  const NUMBER = /-?(?:0|[1-9]\d*)(?:\.\d+)?(?:[eE][+-]?\d+)?/y;
  function readValue(path, keyStart, keyEnd) {
    skipSpace();
    const valueStart = i;
    const c = text[i];
    let container = false;
    if (c === '{') { container = true; readObject(path); }
    else if (c === '[') { container = true; readArray(path); }
    else if (c === '"') readString();
    else if (c === '-' || (c >= '0' && c <= '9')) {
      NUMBER.lastIndex = i;
      const match = NUMBER.exec(text);
      if (!match) fail('malformed number');
      i += match[0].length;
    } else {
      const word = ['true', 'false', 'null'].find((w) => text.startsWith(w, i));
      if (!word) fail(`expected a value, found ${describe()}`);
      i += word.length;
    }
    spans.set(path, { keyStart, keyEnd, valueStart, valueEnd: i, container });
  }

  function readObject(path) {
    ++i;
    skipSpace();
    if (text[i] === '}') { ++i; return; }
    for (let first = true; ; first = false) {
      skipSpace();
      if (text[i] === '}' && !first) fail('a “,” before “}”: JSON allows no trailing comma', text.lastIndexOf(',', i));
      if (text[i] !== '"') fail(`expected a "key" in quotes, found ${describe()}`);
      const keyStart = i;
      const key = readString();
      const keyEnd = i;
      skipSpace();
      if (text[i] !== ':') fail(`expected “:” after the key "${key}", found ${describe()}`);
      ++i;
      readValue(path ? `${path}.${key}` : key, keyStart, keyEnd);
      const afterValue = i;
      skipSpace();
      if (text[i] === ',') { ++i; continue; }
      if (text[i] === '}') { ++i; return; }
      if (text[i] === '"') fail(`missing “,” after the value of "${key}"`, afterValue);
      fail(`expected “,” or “}” after the value of "${key}", found ${describe()}`);
    }
  }

  function readArray(path) {
    ++i;
    skipSpace();
    if (text[i] === ']') { ++i; return; }
    for (let index = 0; ; ++index) {
      skipSpace();
      if (text[i] === ']' && index > 0) fail('a “,” before “]”: JSON allows no trailing comma', text.lastIndexOf(',', i));
      readValue(`${path}[${index}]`, null, null);
      const afterValue = i;
      skipSpace();
      if (text[i] === ',') { ++i; continue; }
      if (text[i] === ']') { ++i; return; }
      if (startsValue()) fail('missing “,” between two entries of the array', afterValue);
      fail(`expected “,” or “]” in the array, found ${describe()}`);
    }
  }

  readValue('', null, null);
  skipSpace();
  if (i < text.length) fail(`unexpected ${describe()} after the end of the JSON value`);
  return spans;
}

// Splits `robot.links[3].length` or `a["b.c"][0]` into ['robot', 'links', 3, 'length'].
export function splitJsonPath(path) {
  const parts = [];
  const re = /\[(\d+)\]|\["((?:[^"\\]|\\.)*)"\]|\.?([^.[\]]+)/g;
  let m;
  while ((m = re.exec(path))) {
    if (m[1] !== undefined) parts.push(Number(m[1]));
    else if (m[2] !== undefined) parts.push(JSON.parse(`"${m[2]}"`));
    else parts.push(m[3]);
  }
  return parts;
}

function joinJsonPath(parts) {
  return parts.reduce((path, p) => (typeof p === 'number' ? `${path}[${p}]` : path ? `${path}.${p}` : p), '');
}

// Where a JSON path sits in the text: {start, end, exact}; when the path names
// a key that is missing, the nearest enclosing value that exists (exact false).
export function locateJsonPath(text, path, spans = scanJson(text)) {
  const parts = splitJsonPath(path || '');
  for (let n = parts.length; n >= 0; --n) {
    const span = spans.get(joinJsonPath(parts.slice(0, n)));
    if (!span) continue;
    const exact = n === parts.length;
    const start = span.keyStart ?? span.valueStart;
    // a scalar is shown with its key; an object or array by its key or opening bracket
    const end = span.container ? (span.keyEnd ?? span.valueStart + 1) : span.valueEnd;
    return { start, end, exact, valueStart: span.valueStart, valueEnd: span.valueEnd };
  }
  return null;
}

export function lineColumn(text, offset) {
  let line = 1, lineStart = 0;
  for (let i = text.indexOf('\n'); i !== -1 && i < offset; i = text.indexOf('\n', i + 1)) { ++line; lineStart = i + 1; }
  return { line, column: offset - lineStart + 1 };
}

// ---- the editor -------------------------------------------------------------


function kilobytes(bytes) { return bytes < 1024 ? `${bytes} B` : `${(bytes / 1024).toFixed(1)} kB`; }

// The server's message repeats the path ("robot.links[3].length: must be > 0, got -0.4"):
// keep the words only.
function plainMessage(error, path) {
  let message = String(error.message || error);
  if (path && message.endsWith(` (${path})`)) message = message.slice(0, -path.length - 3);
  if (path && message.startsWith(`${path}: `)) message = message.slice(path.length + 2);
  return message;
}

// The error's JSON path: `.path` from the page's api.js (ApiError); older ones put it in the message.
function errorPath(error) {
  if (typeof error.path === 'string') return error.path;
  const m = /\(([^()]+)\)$/.exec(String(error.message || ''));
  return m ? m[1] : '';
}

// The validation answer in a phrase: ": planar, 7 DOF, 3 obstacles, xy joystick task, closest_point, 360000 steps".
function describeValidScenario(answer) {
  const parts = [];
  if (answer.kind) parts.push(answer.kind);
  if (answer.dof !== undefined) parts.push(`${answer.dof} DOF`);
  if (answer.obstacles !== undefined) parts.push(`${answer.obstacles} obstacle${answer.obstacles === 1 ? '' : 's'}`);
  if (answer.task) parts.push(`${answer.task.space} ${answer.task.trajectory} task`);
  if (answer.method) parts.push(`method ${answer.method}`);
  if (answer.steps !== undefined) parts.push(`${answer.steps} steps`);
  return parts.length ? `: ${parts.join(', ')}` : '';
}

function isMissingRoute(error) {
  if (error.status === 404 || error.status === 405) return true;
  return error.status === undefined && /no API route|is not allowed here/.test(String(error.message));
}

export class ScenarioEditor {
  // api: {validateScenario, saveScenario, scenarios} (api.js); onStart(name) starts a live run
  constructor(container, { api, onStart }) {
    this.api = api;
    this.onStart = onStart;
    this.savedText = null;    // the text last saved, so Start does not save it twice
    this.savedName = null;
    this.validateAvailable = true;
    this.errorOffset = null;  // where the band marks the last error
    this.build(container);
  }

  build(container) {
    const id = `scenario-editor-${Math.random().toString(36).slice(2, 8)}`;
    this.textarea = element('textarea', {
      id: `${id}-text`, class: 'se-textarea', spellcheck: 'false', wrap: 'off', autocomplete: 'off',
      autocapitalize: 'off', 'aria-describedby': `${id}-position ${id}-message`,
    });
    this.numbers = element('pre', { class: 'se-numbers' });
    this.gutterMark = element('div', { class: 'se-gutter-mark', hidden: '' });
    this.gutterInner = element('div', { class: 'se-gutter-inner' }, [this.gutterMark, this.numbers]);
    this.band = element('div', { class: 'se-band', hidden: '' });
    this.position = element('span', { id: `${id}-position`, class: 'se-position', 'aria-live': 'off' });
    this.size = element('span', { class: 'se-size' });
    this.message = element('div', { id: `${id}-message`, class: 'se-message', role: 'status', 'aria-live': 'polite' });
    this.fileInput = element('input', { type: 'file', accept: '.json,application/json', class: 'se-file', id: `${id}-file`, tabindex: '-1' });

    const button = (label, title, action, cls = '') => {
      const b = element('button', { type: 'button', title, class: cls, text: label });
      b.addEventListener('click', () => action());
      return b;
    };
    this.buttons = {
      upload: button('Upload…', 'Load a .json file from this computer (up to 1 MiB; it is only sent to this server)', () => this.fileInput.click()),
      format: button('Format', 'Re-indent the JSON', () => this.format()),
      validate: button('Validate', 'Check the JSON syntax here, then the scenario on the server (Ctrl+Enter)', () => this.validate()),
      save: button('Save', 'Store it on the server under its "name" (Ctrl+S)', () => this.save()),
      start: button('Save & start', 'Save it, then start a live run of it', () => this.start(), 'se-primary'),
    };
    const close = element('button', { type: 'button', class: 'se-close', 'aria-label': 'Close the scenario editor', title: 'Close (Esc)', text: '×' });
    close.addEventListener('click', () => this.close());

    this.dialog = element('dialog', { class: 'scenario-editor', 'aria-labelledby': `${id}-title` }, [
      element('header', { class: 'se-header' }, [
        element('h2', { id: `${id}-title`, text: 'Scenario editor' }),
        element('span', { class: 'se-hint', text: 'Paste or edit JSON, or upload a file.' }),
        close,
      ]),
      element('div', { class: 'se-toolbar', role: 'toolbar', 'aria-label': 'Scenario actions' },
        [this.buttons.upload, this.fileInput, this.buttons.format, element('span', { class: 'se-spacer' }),
          this.buttons.validate, this.buttons.save, this.buttons.start]),
      element('label', { class: 'se-label', for: `${id}-text`, text: 'Scenario JSON' }),
      element('div', { class: 'se-editor' }, [
        element('div', { class: 'se-gutter', 'aria-hidden': 'true' }, [this.gutterInner]),
        element('div', { class: 'se-text' }, [this.band, this.textarea]),
      ]),
      element('div', { class: 'se-footer' }, [this.position, this.size]),
      this.message,
    ]);
    container.append(this.dialog);

    this.textarea.addEventListener('input', () => { this.clearMark(); this.refresh(); });
    this.textarea.addEventListener('scroll', () => this.syncScroll());
    for (const type of ['keyup', 'click', 'select', 'focus']) this.textarea.addEventListener(type, () => this.showPosition());
    this.fileInput.addEventListener('change', () => this.upload());
    this.dialog.addEventListener('keydown', (event) => {
      if (!(event.ctrlKey || event.metaKey)) return;
      if (event.key === 'Enter') { event.preventDefault(); this.validate(); }
      else if (event.key === 's') { event.preventDefault(); this.save(); }
    });
  }

  open(scenarioJson) {
    const text = typeof scenarioJson === 'string' ? scenarioJson : JSON.stringify(scenarioJson ?? {}, null, 2);
    this.setText(text);
    this.say('info', 'Edit the scenario, then Validate, Save, or Save & start. Its "name" must be new.');
    if (!this.dialog.open) this.dialog.showModal();
    this.textarea.focus({ preventScroll: true });
    this.textarea.setSelectionRange(0, 0);
    this.textarea.scrollTop = 0;
    this.showPosition();
  }

  close() {
    if (this.dialog.open) this.dialog.close();
  }

  get text() { return this.textarea.value; }

  setText(text) {
    this.textarea.value = text;
    this.clearMark();
    this.refresh();
  }

  // ---- display -----------------------------------------------------------

  refresh() {
    const text = this.textarea.value;
    let lines = 1;
    for (let i = text.indexOf('\n'); i !== -1; i = text.indexOf('\n', i + 1)) ++lines;
    if (lines !== this.lineCount) {
      this.lineCount = lines;
      this.numbers.textContent = Array.from({ length: lines }, (_, k) => k + 1).join('\n');
    }
    this.size.textContent = `${lines} lines · ${kilobytes(new Blob([text]).size)}`;
    this.showPosition();
    this.syncScroll();
  }

  showPosition() {
    const { line, column } = lineColumn(this.textarea.value, this.textarea.selectionStart);
    const selected = Math.abs(this.textarea.selectionEnd - this.textarea.selectionStart);
    this.position.textContent = `Line ${line}, column ${column}${selected ? ` · ${selected} selected` : ''}`;
  }

  lineHeight() { return parseFloat(getComputedStyle(this.textarea).lineHeight) || 20; }

  syncScroll() {
    this.gutterInner.style.transform = `translateY(${-this.textarea.scrollTop}px)`;
    if (this.errorOffset !== null) this.band.style.transform = `translateY(${-this.textarea.scrollTop}px)`;
  }

  clearMark() {
    this.errorOffset = null;
    this.band.hidden = true;
    this.gutterMark.hidden = true;
  }

  // Selects [start, end), scrolls it to the upper third and marks its line.
  mark(start, end) {
    const text = this.textarea.value;
    const { line, column } = lineColumn(text, start);
    const lineHeight = this.lineHeight();
    const padding = parseFloat(getComputedStyle(this.textarea).paddingTop) || 0;
    const top = padding + (line - 1) * lineHeight;
    this.errorOffset = start;
    for (const bar of [this.band, this.gutterMark]) {
      bar.style.top = `${top}px`;
      bar.style.height = `${lineHeight}px`;
      bar.hidden = false;
    }
    this.textarea.focus({ preventScroll: true });
    this.textarea.setSelectionRange(start, end);
    // scroll only when the line is not comfortably in view; then to the upper third
    const view = this.textarea;
    if (top < view.scrollTop + lineHeight || top > view.scrollTop + view.clientHeight - 3 * lineHeight) {
      view.scrollTop = Math.max(0, top - view.clientHeight / 3);
    }
    const charWidth = this.charWidth();
    const x = (column - 1) * charWidth;
    this.textarea.scrollLeft = x < this.textarea.clientWidth * 0.7 ? 0 : x - this.textarea.clientWidth / 3;
    this.syncScroll();
    this.showPosition();
  }

  charWidth() {
    if (!this.measure) this.measure = document.createElement('canvas').getContext('2d');
    const style = getComputedStyle(this.textarea);
    this.measure.font = `${style.fontSize} ${style.fontFamily}`;
    return this.measure.measureText('0000000000').width / 10;
  }

  // kind: 'info' | 'ok' | 'error' | 'busy'; actions: [{label, run}]
  say(kind, text, actions = []) {
    this.message.className = `se-message se-${kind}`;
    this.message.replaceChildren(element('span', { class: 'se-message-text', text }));
    for (const { label, run } of actions) {
      const b = element('button', { type: 'button', text: label });
      b.addEventListener('click', run);
      this.message.append(' ', b);
    }
  }

  busy(on) {
    for (const b of Object.values(this.buttons)) b.disabled = on;
  }

  // ---- actions -----------------------------------------------------------

  // JSON.parse, and on failure the tokenizer's position (its words are clearer than V8's).
  parseLocally() {
    const text = this.textarea.value;
    if (!text.trim()) {
      this.say('error', 'The editor is empty: paste a scenario or upload a file.');
      return null;
    }
    try {
      return JSON.parse(text);
    } catch (parseError) {
      let offset = null, words = parseError.message;
      try {
        scanJson(text);
      } catch (e) {
        if (e instanceof JsonSyntaxError) { offset = e.offset; words = e.message; }
      }
      if (offset === null) {
        const m = /position (\d+)/.exec(parseError.message);
        offset = m ? Number(m[1]) : 0;
      }
      const { line, column } = lineColumn(text, offset);
      this.mark(offset, Math.min(offset + 1, text.length));
      this.say('error', `JSON syntax error at line ${line}, column ${column}: ${words}.`,
        [{ label: 'Show', run: () => this.mark(offset, Math.min(offset + 1, text.length)) }]);
      return null;
    }
  }

  // Shows a server error in words and selects the field its path names.
  showFieldError(error, prefix = 'Not valid') {
    const path = errorPath(error);
    const words = plainMessage(error, path);
    const text = this.textarea.value;
    let where = null;
    try { where = path ? locateJsonPath(text, path) : null; } catch { where = null; }
    if (!where) {
      this.clearMark();
      this.say('error', `${prefix}: ${path ? `${path}: ` : ''}${words}`);
      return;
    }
    const { line } = lineColumn(text, where.start);
    const place = where.exact ? `line ${line}` : `it is missing: its place is in the value marked on line ${line}`;
    this.mark(where.start, where.end);
    this.say('error', `${prefix} — ${path}: ${words} (${place}).`, [{ label: 'Show field', run: () => this.mark(where.start, where.end) }]);
  }

  format() {
    const value = this.parseLocally();
    if (value === null) return;
    this.setText(JSON.stringify(value, null, 2));
    this.say('info', 'Re-indented.');
  }

  async validate() {
    const value = this.parseLocally();
    if (value === null) return false;
    this.clearMark();
    if (!this.validateAvailable) {
      this.say('info', 'The JSON syntax is fine. This server cannot check scenarios without storing them; Save checks the rest.');
      return true;
    }
    this.busy(true);
    this.say('busy', 'The JSON syntax is fine; asking the server…');
    try {
      const answer = await this.api.validateScenario(value);
      const summary = describeValidScenario(answer || {});
      if (answer && answer.exists) {
        const suggestion = await this.suggestName(answer.name);
        this.say('ok', `✓ Valid${summary}. The name "${answer.name}" is taken, so Save needs a new one, e.g. "${suggestion}".`,
          [{ label: `Rename to ${suggestion}`, run: () => { this.rename(suggestion); this.say('info', `Renamed to "${suggestion}".`); } }]);
      } else {
        this.say('ok', `✓ Valid${summary}.`);
      }
      return true;
    } catch (error) {
      if (isMissingRoute(error)) {
        this.validateAvailable = false;
        this.say('info', 'The JSON syntax is fine. This server cannot check scenarios without storing them (it has no validation route); Save checks the rest.');
        return true;
      }
      this.showFieldError(error);
      return false;
    } finally {
      this.busy(false);
    }
  }

  // A free name like `name_2`, from the list of stored and built-in scenarios.
  async suggestName(name) {
    let taken = new Set();
    try { taken = new Set((await this.api.scenarios()).map((s) => s.name)); } catch { /* suggest blindly */ }
    const numbered = /^(.+)_(\d{1,3})$/.exec(name);  // name_2 is followed by name_3
    const stem = (numbered ? numbered[1] : name).slice(0, 58);
    for (let n = numbered ? Number(numbered[2]) + 1 : 2; n < 10000; ++n) if (!taken.has(`${stem}_${n}`)) return `${stem}_${n}`;
    return `${stem}_${Date.now() % 100000}`;
  }

  async nameTaken(name) {
    try {
      return (await this.api.scenarios()).some((s) => s.name === name);
    } catch {
      return false;  // the server's 409 will tell
    }
  }

  // Rewrites the "name" value in the text, keeping the rest as typed.
  rename(newName) {
    const text = this.textarea.value;
    const where = locateJsonPath(text, 'name');
    if (!where || !where.exact) return;
    this.setText(text.slice(0, where.valueStart) + JSON.stringify(newName) + text.slice(where.valueEnd));
    const at = locateJsonPath(this.textarea.value, 'name');
    this.textarea.focus({ preventScroll: true });
    this.textarea.setSelectionRange(at.valueStart, at.valueEnd);
    this.showPosition();
  }

  async reportNameTaken(name) {
    const suggestion = await this.suggestName(name);
    const where = locateJsonPath(this.textarea.value, 'name');
    if (where) this.mark(where.start, where.end);
    this.say('error', `A scenario named "${name}" exists already; saved scenarios need a new name. How about "${suggestion}"?`,
      [{ label: `Rename to ${suggestion}`, run: () => { this.rename(suggestion); this.say('info', `Renamed to "${suggestion}": Save again.`); } }]);
  }

  // Returns the saved name, or null after showing why not.
  async save() {
    const value = this.parseLocally();
    if (value === null) return null;
    this.clearMark();
    if (typeof value !== 'object' || Array.isArray(value)) {
      this.say('error', 'A scenario is a JSON object ({ … }).');
      return null;
    }
    const name = value.name;
    if (typeof name !== 'string' || !NAME_PATTERN.test(name)) {
      this.showFieldError({ path: 'name', message: typeof name === 'string'
        ? 'the name must be 1 to 64 letters, digits, “_”, “-” or “.”' : 'a saved scenario needs a "name" string' }, 'Cannot save');
      return null;
    }
    this.busy(true);
    this.say('busy', `Saving "${name}"…`);
    try {
      if (await this.nameTaken(name)) { await this.reportNameTaken(name); return null; }
      await this.api.saveScenario(value);
      this.savedText = this.textarea.value;
      this.savedName = name;
      this.say('ok', `✓ Saved as "${name}".`);
      return name;
    } catch (error) {
      if (error.status === 409 || (error.status === undefined && /exists already/.test(error.message))) await this.reportNameTaken(name);
      else this.showFieldError(error, 'Not saved');
      return null;
    } finally {
      this.busy(false);
    }
  }

  async start() {
    // just saved and unchanged since: start it without saving it twice
    const name = this.savedText === this.textarea.value ? this.savedName : await this.save();
    if (name === null) return;
    this.busy(true);
    this.say('busy', `Starting a live run of "${name}"…`);
    try {
      await this.onStart(name);
      this.say('ok', `✓ Started a live run of "${name}".`);
      this.close();
    } catch (error) {
      this.say('error', `Saved, but the run did not start: ${error.message}`);
    } finally {
      this.busy(false);
    }
  }

  upload() {
    const file = this.fileInput.files[0];
    this.fileInput.value = '';  // choosing the same file again fires change again
    if (!file) return;
    if (file.size > MAX_UPLOAD_BYTES) {
      this.say('error', `${file.name} is ${kilobytes(file.size)}; the editor takes files up to 1 MiB.`);
      return;
    }
    const reader = new FileReader();
    reader.onerror = () => this.say('error', `Could not read ${file.name}.`);
    reader.onload = () => {
      const text = String(reader.result);
      let pretty = text;
      try { pretty = JSON.stringify(JSON.parse(text), null, 2); } catch { /* keep it as is: Validate shows where */ }
      this.setText(pretty);
      this.textarea.scrollTop = 0;
      this.say('info', `Loaded ${file.name} (${kilobytes(file.size)}). Validate, then Save or Save & start.`);
    };
    reader.readAsText(file);
  }
}
