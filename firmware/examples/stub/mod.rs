//! Stand-ins for a HAL's buses, so that the display examples build for any
//! Cortex-M and run under QEMU, which emulates no display panel. Each one
//! implements the embedded-hal 1.0 trait that a real HAL's type
//! implements (the comments name it): replace them by your HAL's and
//! nothing else in the examples changes.
//!
//! Instead of driving pins, [`Spi`] and [`I2c`] count the bytes written
//! and fold them into an FNV-1a checksum, which the examples print: what
//! the display would have received. Nothing is read back and nothing
//! fails (`Infallible`), but the examples pass the drivers' errors on as a
//! real bus's would be.

// Each example uses some of them.
#![allow(dead_code)]

use core::convert::Infallible;

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::{ErrorType as PinErrorType, OutputPin};
use embedded_hal::i2c::{ErrorType as I2cErrorType, Operation as I2cOperation};
use embedded_hal::spi::{ErrorType as SpiErrorType, Operation, SpiDevice};

/// The bytes a bus carried: how many, and their FNV-1a hash.
#[derive(Clone, Copy, Debug)]
pub struct Wire {
    /// Bytes written.
    pub bytes: u64,
    /// FNV-1a (32-bit) of every byte written, in order.
    pub hash: u32,
}

impl Default for Wire {
    fn default() -> Self {
        Wire {
            bytes: 0,
            hash: 0x811c_9dc5,
        }
    }
}

impl Wire {
    /// Adds `data` to the record.
    pub fn write(&mut self, data: &[u8]) {
        for &b in data {
            self.hash = (self.hash ^ u32::from(b)).wrapping_mul(0x0100_0193);
        }
        self.bytes += data.len() as u64;
    }
}

/// An SPI device (a HAL's SPI bus with its chip-select pin, e.g.
/// `embedded_hal_bus::spi::ExclusiveDevice`): `SpiDevice`.
#[derive(Debug, Default)]
pub struct Spi {
    /// What was written.
    pub wire: Wire,
}

impl SpiErrorType for Spi {
    type Error = Infallible;
}

impl SpiDevice for Spi {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), Infallible> {
        for op in operations {
            match op {
                Operation::Write(data) => self.wire.write(data),
                Operation::Transfer(_, data) => self.wire.write(data),
                Operation::TransferInPlace(data) => self.wire.write(data),
                Operation::Read(_) | Operation::DelayNs(_) => {}
            }
        }
        Ok(())
    }
}

/// An I2C bus (a HAL's I2C peripheral): `embedded_hal::i2c::I2c`.
#[derive(Debug, Default)]
pub struct I2c {
    /// What was written (the address bytes left out).
    pub wire: Wire,
}

impl I2cErrorType for I2c {
    type Error = Infallible;
}

impl embedded_hal::i2c::I2c for I2c {
    fn transaction(
        &mut self,
        _address: u8,
        operations: &mut [I2cOperation<'_>],
    ) -> Result<(), Infallible> {
        for op in operations {
            if let I2cOperation::Write(data) = op {
                self.wire.write(data);
            }
        }
        Ok(())
    }
}

/// An output pin (a display's data/command or reset line): `OutputPin`.
#[derive(Debug, Default)]
pub struct Pin;

impl PinErrorType for Pin {
    type Error = Infallible;
}

impl OutputPin for Pin {
    fn set_low(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// A delay (a HAL's timer delay): `DelayNs`. Returns at once: QEMU's
/// display-less machine has nothing to wait for.
#[derive(Debug, Default)]
pub struct Delay;

impl DelayNs for Delay {
    fn delay_ns(&mut self, _ns: u32) {}
}
