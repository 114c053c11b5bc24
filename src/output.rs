//! Writing images and animations: PNG, PPM, GIF, frame names.
