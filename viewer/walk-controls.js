// Walking: drag to look, W A S D to move along the view, Q / E down and up,
// shift for ten times the speed, the wheel to change the speed, R back to the
// starting camera. Drag rather than pointer lock, so that the cursor stays
// free to point at a surface for the luminance readout.
//
// The orientation is the starting camera's turned by a yaw about the world's
// +Y (up, as Radiant's scenes have it) and a pitch about the camera's own x
// axis: q = yaw · q₀ · pitch. The file's camera is thus reproduced exactly
// (no Euler-angle round trip), roll included.
import * as THREE from 'three';

const MOVE_KEYS = {
  KeyW: [0, 0, -1],
  KeyS: [0, 0, 1],
  KeyA: [-1, 0, 0],
  KeyD: [1, 0, 0],
  KeyQ: [0, -1, 0],
  KeyE: [0, 1, 0],
  ArrowUp: [0, 0, -1],
  ArrowDown: [0, 0, 1],
  ArrowLeft: [-1, 0, 0],
  ArrowRight: [1, 0, 0],
};
const MAX_PITCH = THREE.MathUtils.degToRad(89);

export class WalkControls {
  /**
   * @param camera the PerspectiveCamera to move
   * @param element what receives mouse and keyboard events
   * @param sceneSize the scene's bounding-box diagonal, metres: walking crosses it in about 4 s
   */
  constructor(camera, element, sceneSize) {
    this.camera = camera;
    this.element = element;
    this.speed = sceneSize / 4; // m/s
    this.pressed = new Set();
    this.yaw = 0;
    this.pitch = 0;
    this.startPosition = camera.position.clone();
    this.startQuaternion = camera.quaternion.clone();
    this.onChange = () => {};
    this.dragging = false;

    element.addEventListener('pointerdown', (e) => {
      if (e.button !== 0) return;
      this.dragging = true;
      element.setPointerCapture(e.pointerId);
      element.focus();
    });
    element.addEventListener('pointerup', (e) => {
      this.dragging = false;
      element.releasePointerCapture(e.pointerId);
    });
    element.addEventListener('pointermove', (e) => {
      if (!this.dragging) return;
      // One pixel turns by one pixel's angle, so the surface stays under the cursor.
      const radiansPerPixel = THREE.MathUtils.degToRad(camera.fov) / element.clientHeight;
      this.yaw -= e.movementX * radiansPerPixel;
      this.pitch = THREE.MathUtils.clamp(this.pitch - e.movementY * radiansPerPixel, -MAX_PITCH, MAX_PITCH);
      this.applyOrientation();
      this.onChange();
    });
    element.addEventListener(
      'wheel',
      (e) => {
        e.preventDefault();
        this.speed *= e.deltaY < 0 ? 1.25 : 0.8;
      },
      { passive: false },
    );
    window.addEventListener('keydown', (e) => {
      if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
      if (e.code === 'KeyR') {
        this.reset();
        this.onChange();
        return;
      }
      if (MOVE_KEYS[e.code] || e.key === 'Shift') this.pressed.add(e.code);
    });
    window.addEventListener('keyup', (e) => this.pressed.delete(e.code));
    window.addEventListener('blur', () => this.pressed.clear());
  }

  reset() {
    this.yaw = 0;
    this.pitch = 0;
    this.camera.position.copy(this.startPosition);
    this.applyOrientation();
  }

  applyOrientation() {
    const yaw = new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 1, 0), this.yaw);
    const pitch = new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), this.pitch);
    this.camera.quaternion.copy(yaw).multiply(this.startQuaternion).multiply(pitch);
    this.camera.updateMatrixWorld();
  }

  get moving() {
    for (const code of this.pressed) if (MOVE_KEYS[code]) return true;
    return false;
  }

  /** Moves by the keys held for `seconds`; true if the camera moved. */
  update(seconds) {
    const direction = new THREE.Vector3();
    for (const code of this.pressed) if (MOVE_KEYS[code]) direction.add(new THREE.Vector3(...MOVE_KEYS[code]));
    if (direction.lengthSq() === 0) return false;
    const fast = this.pressed.has('ShiftLeft') || this.pressed.has('ShiftRight') ? 10 : 1;
    // Up and down along the world's up; the rest along the view.
    const vertical = direction.y;
    direction.y = 0;
    direction.normalize().applyQuaternion(this.camera.quaternion);
    direction.y += vertical;
    this.camera.position.addScaledVector(direction, this.speed * fast * Math.min(seconds, 0.1));
    this.camera.updateMatrixWorld();
    return true;
  }
}
