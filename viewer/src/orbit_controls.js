// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Orbit, zoom and pan around a target point for the report viewer: left button turns the
// camera around the target, right button (or shift + left) pans, the wheel zooms. Calls
// `onChange` after every move, so that the page draws only when something changed.

class Orbit_controls {
  constructor(camera, element, onChange) {
    this.camera = camera;
    this.element = element;
    this.onChange = onChange;
    this.target = new THREE.Vector3();
    this.distance = 1;
    this.azimuth = 0.6;   // around the up axis (z)
    this.elevation = 0.5; // above the xy plane
    this.dragging = null;
    this.last = null;
    element.addEventListener('contextmenu', (e) => e.preventDefault());
    element.addEventListener('pointerdown', (e) => this.pointerDown(e));
    element.addEventListener('pointermove', (e) => this.pointerMove(e));
    element.addEventListener('pointerup', (e) => this.pointerUp(e));
    element.addEventListener('wheel', (e) => this.wheel(e), { passive: false });
  }

  // Looks at `target` from `distance`, keeping the direction of view.
  look_at(target, distance) {
    this.target.copy(target);
    this.distance = Math.max(distance, 1e-12);
    this.update();
  }

  update() {
    const c = Math.cos(this.elevation);
    const offset = new THREE.Vector3(c * Math.cos(this.azimuth), c * Math.sin(this.azimuth), Math.sin(this.elevation));
    this.camera.position.copy(this.target).addScaledVector(offset, this.distance);
    this.camera.up.set(0, 0, 1);
    this.camera.near = this.distance / 1000;
    this.camera.far = this.distance * 1000;
    this.camera.lookAt(this.target);
    this.camera.updateProjectionMatrix();
    this.onChange();
  }

  pointerDown(e) {
    this.dragging = e.button === 2 || e.shiftKey ? 'pan' : 'rotate';
    this.last = { x: e.clientX, y: e.clientY };
    this.element.setPointerCapture(e.pointerId);
  }

  pointerMove(e) {
    if (!this.dragging) return;
    const dx = e.clientX - this.last.x;
    const dy = e.clientY - this.last.y;
    this.last = { x: e.clientX, y: e.clientY };
    if (this.dragging === 'rotate') {
      this.azimuth -= dx * 0.01;
      this.elevation = Math.max(-1.55, Math.min(1.55, this.elevation + dy * 0.01));
    } else {
      const height = this.element.clientHeight || 1;
      const scale = 2 * this.distance * Math.tan((this.camera.fov * Math.PI) / 360) / height;
      const right = new THREE.Vector3().setFromMatrixColumn(this.camera.matrix, 0);
      const up = new THREE.Vector3().setFromMatrixColumn(this.camera.matrix, 1);
      this.target.addScaledVector(right, -dx * scale).addScaledVector(up, dy * scale);
    }
    this.update();
  }

  pointerUp(e) {
    this.dragging = null;
    this.element.releasePointerCapture(e.pointerId);
  }

  wheel(e) {
    e.preventDefault();
    this.distance *= Math.exp(e.deltaY * 0.001);
    this.update();
  }
}
