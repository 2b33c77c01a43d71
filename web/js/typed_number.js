// Numbers typed by a person, read one way only: a decimal comma is a decimal
// point ("0,3" is 0.3, never 3); text that could be read two ways ("1,234.5",
// "1,2,3") or is not a number is refused with a message. Fields are text
// fields (inputmode decimal): a number field drops the comma and sends "03".

const NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i;

// {value} or {error}: text → number, within [min, max] when given.
export function parseTypedNumber(text, { min = -Infinity, max = Infinity, unit = '' } = {}) {
  const raw = String(text).trim().replace(/\s+/g, '');
  const bounds = Number.isFinite(max) ? (Number.isFinite(min) ? ` in [${min}, ${max}]` : ` ≤ ${max}`) : (Number.isFinite(min) ? ` ≥ ${min}` : '');
  const range = `a number${bounds}${unit ? ` ${unit}` : ''}`;
  if (raw === '') return { error: `type ${range}` };
  const commas = (raw.match(/,/g) || []).length;
  if (commas > 1 || (commas === 1 && raw.includes('.'))) return { error: `"${text}" can be read two ways: write one decimal separator, as 0.3 or 0,3` };
  const normal = raw.replace(',', '.');
  if (!NUMBER.test(normal)) return { error: `"${text}" is not a number` };
  const value = Number(normal);
  if (!Number.isFinite(value)) return { error: `"${text}" is too large` };
  if (value < min || value > max) return { error: `${value} is out of range: type ${range}` };
  return { value };
}

// The field's message, beside it: made once, after `after` (the field itself
// unless its row is given), found again by the field's aria-describedby.
let notes = 0;
function messageOf(field, after = field) {
  const id = field.getAttribute('aria-describedby');
  let note = id && document.getElementById(id);
  if (!note) {
    note = document.createElement('span');
    note.className = 'field-error';
    note.setAttribute('role', 'alert');
    note.id = `field-error-${++notes}`;
    after.after(note);
    field.setAttribute('aria-describedby', note.id);
  }
  return note;
}

// A refused value: the field is marked with the message beside it and shows the current value again.
export function refuse(field, message, current, after = field) {
  mark(field, message, after);
  field.value = current;
}

// A field marked as wrong, the message beside it (after `after`), its text
// kept to be corrected (a list of parameters, not one number to put back).
export function mark(field, message, after = field) {
  const note = messageOf(field, after);
  note.textContent = message;
  note.hidden = false;
  field.setAttribute('aria-invalid', 'true');
}

// An accepted value clears the field's mark.
export function accept(field) {
  field.removeAttribute('aria-invalid');
  const id = field.getAttribute('aria-describedby');
  const note = id && document.getElementById(id);
  if (note && note.classList.contains('field-error')) { note.textContent = ''; note.hidden = true; }
}

// Reads `field` on change: onValue(number) when it parses, else refuse with
// the message (after `after`: the field, or its row) and put back current() (a string).
export function typedNumber(field, { min, max, unit, current, onValue, after = field }) {
  field.onchange = () => {
    const read = parseTypedNumber(field.value, { min, max, unit });
    if ('error' in read) { refuse(field, read.error, current(), after); return; }
    accept(field);
    onValue(read.value);
  };
}
