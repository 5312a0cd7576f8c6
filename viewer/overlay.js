// The overlay: the tone operator and its parameters (the same names and
// defaults as `radiant tonemap`'s flags), the description of the constants the
// operator adapted to, and the readouts under the cursor. Hidden by `ui=0`.
import { TONE_OPERATORS, findToneOperator } from './tone-operators.js';

const $ = (id) => document.getElementById(id);

function formatPhotometric(value, unit) {
  if (!Number.isFinite(value)) return '–';
  const digits = value >= 100 ? 0 : value >= 10 ? 1 : value >= 1 ? 2 : 3;
  return `${value.toFixed(digits)} ${unit}`;
}

export class Overlay {
  /**
   * @param settings {operator: name, parameters: {name: value}} — edited in place
   * @param onChange called after the user changed a setting
   */
  constructor(settings, visible, onChange) {
    this.settings = settings;
    this.onChange = onChange;
    $('overlay').hidden = !visible;
    const select = $('operator');
    for (const op of TONE_OPERATORS) {
      const option = document.createElement('option');
      option.value = op.name;
      option.textContent = op.name;
      option.title = op.summary;
      select.append(option);
    }
    select.value = settings.operator;
    select.addEventListener('change', () => {
      settings.operator = select.value;
      this.buildParameters();
      onChange();
    });
    this.buildParameters();
  }

  /** One control per parameter of the current operator: a slider for exposure, number fields for the rest. */
  buildParameters() {
    const op = findToneOperator(this.settings.operator);
    const box = $('parameters');
    box.replaceChildren();
    for (const spec of op.parameters) {
      // linear's key counts only with auto exposure (radiant refuses it otherwise).
      if (op.name === 'linear' && spec.name === 'key' && this.settings.parameters.exposure !== 'auto') continue;
      const label = document.createElement('label');
      label.textContent = `${spec.label} `;
      const value = this.settings.parameters[spec.name];
      if (spec.name === 'exposure') {
        const slider = document.createElement('input');
        slider.type = 'range';
        [slider.min, slider.max] = spec.slider;
        slider.step = spec.step;
        slider.id = 'exposure';
        const shown = document.createElement('span');
        const auto = document.createElement('input');
        auto.type = 'checkbox';
        const autoLabel = document.createElement('label');
        autoLabel.append(auto, ' auto');
        const sync = () => {
          const v = this.settings.parameters.exposure ?? spec.default;
          auto.checked = v === 'auto';
          slider.disabled = auto.checked;
          if (v !== 'auto') slider.value = v;
          shown.textContent = v === 'auto' ? ' auto' : ` ${Number(v).toFixed(1)}`;
        };
        slider.addEventListener('input', () => {
          this.settings.parameters.exposure = Number(slider.value);
          sync();
          this.onChange();
        });
        auto.addEventListener('change', () => {
          this.settings.parameters.exposure = auto.checked ? 'auto' : Number(slider.value);
          this.buildParameters();
          this.onChange();
        });
        sync();
        label.append(slider, shown);
        box.append(label, autoLabel);
        continue;
      }
      const input = document.createElement('input');
      input.type = 'number';
      input.step = spec.step;
      if (Number.isFinite(spec.min)) input.min = spec.min;
      if (Number.isFinite(spec.max)) input.max = spec.max;
      input.placeholder = spec.default === null ? (spec.unset ?? 'from the view') : String(spec.default);
      input.value = value === undefined || value === null || value === spec.default ? '' : value;
      input.addEventListener('change', () => {
        const x = input.value === '' ? null : Number(input.value);
        this.settings.parameters[spec.name] = x !== null && x >= spec.min && x <= spec.max ? x : null;
        this.onChange();
      });
      label.append(input);
      box.append(label);
    }
  }

  describe(text) {
    $('describe').textContent = text;
  }

  /** luminance cd/m² and illuminance lux under the cursor; NaN: nothing there. */
  readout(luminance, illuminance) {
    $('luminance').textContent = formatPhotometric(luminance, 'cd/m²');
    $('illuminance').textContent = formatPhotometric(illuminance, 'lx');
  }

  frameRate(fps) {
    $('fps').textContent = `${fps.toFixed(0)} frames/s`;
  }
}

/** A message over the page for what the viewer cannot show (shown even with ui=0). */
export function showError(message) {
  const box = $('error');
  box.textContent = message;
  box.hidden = false;
  document.title = `error: ${message.split('\n')[0]}`;
}
