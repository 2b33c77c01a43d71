// The page's layout: column borders that drag (and move with the arrow keys
// when focused), their widths remembered in this browser, and the keyboard
// shortcut list on "?".
import { isTyping } from './dom.js';

const STORE_KEY = 'rrlab.layout';
const LIMITS = { left: [180, 560], right: [220, 640] };
const STEP = 16;  // px per arrow key

function load() {
  try { return JSON.parse(localStorage.getItem(STORE_KEY)) || {}; } catch { return {}; }
}

function apply(widths) {
  const main = document.querySelector('main');
  for (const side of ['left', 'right']) {
    if (Number.isFinite(widths[side])) main.style.setProperty(`--${side}-width`, `${widths[side]}px`);
  }
}

const clamp = (side, px) => Math.round(Math.min(LIMITS[side][1], Math.max(LIMITS[side][0], px)));

export function setupLayout() {
  const widths = load();
  apply(widths);
  const save = () => { try { localStorage.setItem(STORE_KEY, JSON.stringify(widths)); } catch { /* private mode: not remembered */ } };
  for (const splitter of document.querySelectorAll('.splitter')) {
    const side = splitter.dataset.side;
    const column = document.getElementById(side);
    const set = (px) => { widths[side] = clamp(side, px); apply(widths); };
    splitter.addEventListener('pointerdown', (e) => {
      if (e.button !== 0) return;
      e.preventDefault();
      splitter.setPointerCapture(e.pointerId);
      const start = e.clientX, from = column.getBoundingClientRect().width;
      const move = (m) => set(side === 'left' ? from + m.clientX - start : from - (m.clientX - start));
      const up = () => {
        splitter.removeEventListener('pointermove', move);
        splitter.removeEventListener('pointerup', up);
        splitter.removeEventListener('pointercancel', up);
        save();
      };
      splitter.addEventListener('pointermove', move);
      splitter.addEventListener('pointerup', up);
      splitter.addEventListener('pointercancel', up);
    });
    splitter.addEventListener('keydown', (e) => {
      if (e.key !== 'ArrowLeft' && e.key !== 'ArrowRight') return;
      e.preventDefault();
      const wider = (e.key === 'ArrowRight') === (side === 'left');
      set(column.getBoundingClientRect().width + (wider ? STEP : -STEP));
      save();
    });
    splitter.addEventListener('dblclick', () => { delete widths[side]; document.querySelector('main').style.removeProperty(`--${side}-width`); save(); });
  }
  const keys = document.getElementById('keys-dialog');
  document.getElementById('show-keys').onclick = () => keys.showModal();
  window.addEventListener('keydown', (e) => {
    if (e.key === '?' && !isTyping(e.target, e.key) && !keys.open) { e.preventDefault(); keys.showModal(); }
  });
}
