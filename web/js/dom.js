// Small DOM helpers shared by the panels.

// An element with attributes ('text' sets its text) and children.
export function element(tag, attributes = {}, children = []) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes)) {
    if (name === 'text') node.textContent = value;
    else node.setAttribute(name, value);
  }
  for (const child of children) node.append(child);
  return node;
}

// Keys typed into a field, or pressed inside a dialog, are not page shortcuts.
// A slider, a tick box or a button takes only the keys it acts on itself (a
// slider: arrows, Home, End, Page keys): after a click on the replay
// scrubber, space , and . still work.
const SLIDER_KEYS = new Set(['ArrowLeft', 'ArrowRight', 'ArrowUp', 'ArrowDown', 'Home', 'End', 'PageUp', 'PageDown']);
export const isTyping = (target, key = '') => {
  if (!(target instanceof HTMLElement)) return false;
  if (target.closest('dialog') !== null || target.isContentEditable) return true;
  if (target.tagName === 'INPUT' && ['range', 'checkbox', 'radio', 'button'].includes(target.type)) return target.type === 'range' && SLIDER_KEYS.has(key);
  return ['INPUT', 'TEXTAREA', 'SELECT'].includes(target.tagName);
};

// Text made safe for innerHTML (names and descriptions come from users' scenarios).
export function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]);
}

// A value as the tables and panels print it: 4 decimals, exponents beyond
// them, yes/no, and a dash for none.
export function fmt(v) {
  if (v === null || v === undefined) return '—';
  if (typeof v === 'boolean') return v ? 'yes' : 'no';
  if (typeof v !== 'number') return String(v);
  if (Number.isInteger(v)) return String(v);
  return Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(3) : v.toFixed(4);
}
