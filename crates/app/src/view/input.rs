//! The keyboard and mouse as the fly camera reads them: W A S D Q E held, the mouse moved
//! with the right button held over the picture, the wheel over the picture, R, and the keys
//! that save (P: screenshot, K: settings).
use super::camera::FlyInput;
use std::collections::HashSet;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::keyboard::{KeyCode, PhysicalKey};

/// What a key asks of the window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KeyCommand {
    Screenshot,
    SaveSettings,
}

/// The keyboard and mouse as the camera reads them.
#[derive(Default)]
pub struct Input {
    pub held: HashSet<KeyCode>,
    /// Keys pressed since the last frame: a key pressed and released between two (slow)
    /// frames still moves the camera for one frame.
    pressed: HashSet<KeyCode>,
    looking: bool,
    cursor: Option<(f64, f64)>,
    look: (f32, f32),
    wheel: f32,
    pub reset: bool,
}

impl Input {
    /// The input gathered since the last frame (motion and wheel are consumed).
    pub fn take(&mut self) -> FlyInput {
        let down = |k| {
            f32::from(u8::from(
                self.held.contains(&k) || self.pressed.contains(&k),
            ))
        };
        let axis = |plus, minus| down(plus) - down(minus);
        let input = FlyInput {
            forward: axis(KeyCode::KeyW, KeyCode::KeyS),
            right: axis(KeyCode::KeyD, KeyCode::KeyA),
            up: axis(KeyCode::KeyE, KeyCode::KeyQ),
            look: self.look,
            wheel: self.wheel,
            reset: self.reset,
        };
        (self.look, self.wheel, self.reset) = ((0.0, 0.0), 0.0, false);
        self.pressed.clear();
        input
    }
    /// Takes in a window event; `consumed` when egui took it, `picture` the picture's pixel
    /// rectangle (left, top, right, bottom) where the mouse moves the camera.
    pub fn handle(
        &mut self,
        event: &WindowEvent,
        consumed: bool,
        picture: [f64; 4],
    ) -> Option<KeyCommand> {
        let over = |c: Option<(f64, f64)>| {
            c.is_some_and(|(x, y)| {
                x >= picture[0] && y >= picture[1] && x < picture[2] && y < picture[3]
            })
        };
        match event {
            WindowEvent::KeyboardInput { event, .. } => {
                let pressed = event.state == ElementState::Pressed;
                // A key typed into the panel is the panel's; a release always lets go.
                let PhysicalKey::Code(code) = event.physical_key else {
                    return None;
                };
                if pressed && consumed {
                    return None;
                }
                if !pressed {
                    self.held.remove(&code);
                    return None;
                }
                self.held.insert(code);
                self.pressed.insert(code);
                match code {
                    _ if event.repeat => None,
                    KeyCode::KeyR => {
                        self.reset = true;
                        None
                    }
                    KeyCode::KeyP => Some(KeyCommand::Screenshot),
                    KeyCode::KeyK => Some(KeyCommand::SaveSettings),
                    _ => None,
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Right,
                ..
            } => {
                self.looking = *state == ElementState::Pressed && over(self.cursor);
                None
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let (true, Some((x, y))) = (self.looking, self.cursor) {
                    self.look.0 += (position.x - x) as f32;
                    self.look.1 += (position.y - y) as f32;
                }
                self.cursor = Some((position.x, position.y));
                None
            }
            WindowEvent::MouseWheel { delta, .. } if over(self.cursor) => {
                self.wheel += match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                None
            }
            _ => None,
        }
    }
}
