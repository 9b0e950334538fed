//! Which lights a scene is drawn with: its own, or the default lighting glTF viewers
//! give a file without lights (most real assets carry none, and would render black).

use glam::{DQuat, DVec3};

use super::{Environment, Light, LightKind, Scene};

/// The lights a scene is drawn with.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Lighting {
    /// The scene's own lights; a glTF file without any that emit gets the defaults (with a
    /// warning). Built-in scenes keep what they define (`builtin:unlit` has no lights by
    /// design).
    #[default]
    Auto,
    /// Only the scene's own lights, even none.
    File,
    /// Only the defaults, replacing the scene's lights and ambient term.
    Default,
    /// The scene's lights and the defaults.
    Both,
}

/// The default environment's intensity: a white surface facing up reflects about 1.
pub const DEFAULT_ENVIRONMENT_INTENSITY: f32 = 1.0;
/// The default headlight's illuminance in lux: the brightness of the studio's sky.
pub const HEADLIGHT_LUX: f32 = 1.5;

impl Lighting {
    /// Every choice, in the order the command line lists them.
    pub const ALL: [Lighting; 4] = [
        Lighting::Auto,
        Lighting::File,
        Lighting::Default,
        Lighting::Both,
    ];

    /// Its name, as the command line spells it.
    pub fn name(self) -> &'static str {
        match self {
            Lighting::Auto => "auto",
            Lighting::File => "file",
            Lighting::Default => "default",
            Lighting::Both => "both",
        }
    }

    /// The choice named `name`, or `None`.
    pub fn named(name: &str) -> Option<Lighting> {
        Lighting::ALL.into_iter().find(|l| l.name() == name)
    }
}

impl Scene {
    /// The scene lit as `lighting` says. Adding the defaults adds a warning that says
    /// so (and, for [`Lighting::Auto`], why).
    pub fn lit(mut self, lighting: Lighting) -> Scene {
        let emits = self.lights.iter().any(Light::emits);
        let is_file = !self.name.starts_with(super::BUILTIN_PREFIX);
        let (replace, add) = match lighting {
            Lighting::Auto => (false, is_file && !emits),
            Lighting::File => (false, false),
            Lighting::Default => (true, true),
            Lighting::Both => (false, true),
        };
        if replace {
            self.lights.clear();
            self.ambient = [0.0; 3];
        }
        if add {
            let why = match (lighting, self.lights.len()) {
                (Lighting::Auto, 0) => "it has no lights; ".to_owned(),
                // Named, so a light that was meant to shine is found.
                (Lighting::Auto, dark) => {
                    let mut names: Vec<&str> = self
                        .lights
                        .iter()
                        .take(3)
                        .map(|l| l.name.as_str())
                        .collect();
                    let more = format!("{} more", dark - names.len());
                    if dark > names.len() {
                        names.push(&more);
                    }
                    format!(
                        "none of its {dark} light(s) emits anything ({}: intensity or \
                         color 0); ",
                        names.join(", ")
                    )
                }
                _ => String::new(),
            };
            self.lights.push(headlight(&self));
            self.environment = Some(Environment {
                intensity: DEFAULT_ENVIRONMENT_INTENSITY,
            });
            self.warnings.push(format!(
                "{}: {why}lit by the default lighting: a neutral studio environment \
                 (intensity {DEFAULT_ENVIRONMENT_INTENSITY}) and a {HEADLIGHT_LUX} lux \
                 headlight (--lights file|default|both chooses)",
                self.name
            ));
        }
        self
    }
}

/// A directional light from just above and left of the camera, so that faces toward the
/// viewer are lit and their relief still shows.
fn headlight(scene: &Scene) -> Light {
    let camera = &scene.camera;
    let tilt = DQuat::from_rotation_x(-0.25) * DQuat::from_rotation_y(-0.2);
    let direction = (camera.orientation * tilt * DVec3::NEG_Z).normalize();
    Light {
        name: "default headlight".to_string(),
        kind: LightKind::Directional,
        color: [1.0; 3],
        intensity: HEADLIGHT_LUX,
        position: camera.position,
        direction: direction.as_vec3(),
        range: None,
    }
}
