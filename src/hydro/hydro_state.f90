!> Node and zone fields of the staggered scheme, and the hydro options.
module hydro_state
  use core_kinds, only: rk, i8
  implicit none
  private

  integer, parameter, public :: HOURGLASS_NONE = 0
  integer, parameter, public :: HOURGLASS_VISCOUS = 1
  integer, parameter, public :: HOURGLASS_STIFFNESS = 2
  integer, parameter, public :: VISCOSITY_SCALAR = 1 !< zone-centred q (von Neumann-Richtmyer)
  integer, parameter, public :: VISCOSITY_EDGE = 2 !< edge-centred q (Caramana-Shashkov-Whalen)

  !> Numerical options of the hydro scheme (deck group &control / &hydro).
  type, public :: hydro_options_t
    real(rk) :: cfl = 0.5_rk !< Courant factor
    real(rk) :: dt_initial = 0.0_rk !< first step; 0 = from the CFL limit
    real(rk) :: dt_max = huge(1.0_rk) !< largest step
    real(rk) :: dt_min = 1.0e-12_rk !< a step below this stops the run
    real(rk) :: dt_growth = 1.1_rk !< largest growth of dt per cycle
    real(rk) :: dvol_max = 0.1_rk !< largest relative volume change per cycle
    real(rk) :: q_linear = 0.5_rk !< linear viscosity coefficient C1
    real(rk) :: q_quadratic = 2.0_rk / 3.0_rk !< quadratic viscosity coefficient C2
    logical :: q_limiter = .true. !< monotonic limiter of the viscosity
    logical :: single_stage = .false. !< one force evaluation per cycle (experimental)
    logical :: q_linear_limited = .true. !< the limiter acts on the linear term too
    integer :: viscosity = VISCOSITY_SCALAR !< VISCOSITY_* form of the artificial viscosity
    real(rk) :: heat_flux_linear = 0.0_rk !< artificial heat flux coefficient a (0: off)
    real(rk) :: heat_flux_quadratic = 0.0_rk !< artificial heat flux coefficient b (0: off)
    integer :: hourglass = HOURGLASS_VISCOUS !< HOURGLASS_* type
    real(rk) :: hourglass_coefficient = 0.1_rk !< Flanagan-Belytschko coefficient
  end type hydro_options_t

  !> The fields. Nodes 1..nnode_owned and zones 1..nzone_owned are owned.
  type, public :: state_t
    real(rk), allocatable :: node_position(:, :) !< (3, nnode) x^n
    !> (3, nnode) x at t = 0 (the dumps' displacement; restart dumps carry it)
    real(rk), allocatable :: node_position_initial(:, :)
    real(rk), allocatable :: node_velocity(:, :) !< (3, nnode) v^n
    real(rk), allocatable :: node_mass(:) !< fixed nodal mass
    real(rk), allocatable :: node_force(:, :) !< (3, nnode) force of the stage
    real(rk), allocatable :: node_position_old(:, :) !< x^n during a cycle
    real(rk), allocatable :: node_velocity_old(:, :) !< v^n during a cycle
    real(rk), allocatable :: node_velocity_half(:, :) !< time-centred velocity of a stage
    real(rk), allocatable :: zone_mass(:) !< fixed zone mass
    real(rk), allocatable :: zone_volume(:)
    real(rk), allocatable :: zone_density(:)
    real(rk), allocatable :: zone_energy(:) !< specific internal energy
    real(rk), allocatable :: zone_energy_old(:) !< e^n during a cycle
    real(rk), allocatable :: zone_pressure(:)
    real(rk), allocatable :: zone_viscosity(:) !< artificial viscosity q
    real(rk), allocatable :: zone_sound_speed(:)
    real(rk), allocatable :: zone_length(:) !< characteristic length
    real(rk), allocatable :: zone_divergence(:) !< div v = (dV/dt)/V
    real(rk), allocatable :: zone_gradient(:, :) !< (3, nzone) stretching rates (limiter)
    !> edge viscosity only, (2, nzone): 1 - psi, psi the zone's limiter (1), and
    !> the zone's strong-shock factor (gamma + 1)/4 (2)
    real(rk), allocatable :: zone_edge_q(:, :)
    real(rk), allocatable :: zone_bmatrix(:, :, :) !< (3, 8, nzone) dV/dx at x^n
    real(rk), allocatable :: zone_hourglass(:, :, :) !< (3, 4, nzone) stiffness state
    real(rk), allocatable :: zone_hourglass_new(:, :, :) !< its update during a cycle
    real(rk), allocatable :: corner_force(:, :, :) !< (3, 8, nzone)
    real(rk), allocatable :: zone_stress(:, :) !< (6, nzone) deviatoric stress (strength only)
    real(rk), allocatable :: zone_stress_half(:, :) !< its value at t^n+1/2
    real(rk), allocatable :: zone_plastic_strain(:) !< equivalent plastic strain
    !> plastic work of the zone so far, sum of sbar dp V over the final strength
    !> updates (strength only; restart data)
    real(rk), allocatable :: zone_plastic_work(:)
    !> energy the hourglass forces have taken from the zone's nodes so far,
    !> sum of -dt F_hg . v over the corrector stages (hourglass control on
    !> only; restart data)
    real(rk), allocatable :: zone_hourglass_work(:)
    !> failure damage D = sum(deps_p / eps_f), 1 when failed (a material with a
    !> failure model or a spall strength only; dumps and restart)
    real(rk), allocatable :: zone_damage(:)
    !> erosion on only: 1 live, 0 eroded (dumps and restart; ghosts from the halo)
    real(rk), allocatable :: zone_alive(:)
    !> &erosion volume_ratio only: zone volume at t = 0 (from the initial positions)
    real(rk), allocatable :: zone_volume_initial(:)
    !> erosion on only: the kinetic energy an owned node took with it when the
    !> last live zone using it was eroded (restart data)
    real(rk), allocatable :: node_eroded_kinetic(:)
    integer, allocatable :: eroded_zones(:) !< erosion on only: local eroded zones, ascending
    integer, allocatable :: dead_nodes(:) !< erosion on only: owned nodes no live zone uses
    !> the run's first stable step (&erosion dt_fraction's reference; restart data)
    real(rk) :: dt_reference = 0.0_rk
    !> &control stop_block's kinetic energy at t = 0 (restart data)
    real(rk) :: stop_kinetic_initial = 0.0_rk
    real(rk) :: time = 0.0_rk !< t^n
    real(rk) :: dt = 0.0_rk !< step of the current cycle
    real(rk) :: dt_previous = 0.0_rk !< step of the previous cycle (0 before the first)
    integer(i8) :: cycle = 0 !< cycles done
    real(rk) :: boundary_work = 0.0_rk !< work done on the body by boundaries (diagnostic)
    real(rk) :: energy_initial = 0.0_rk !< total energy at t = 0 (diagnostic)
  end type state_t

  public :: state_init

contains

  !> Allocate every field for nnode nodes and nzone zones, zeroed.
  subroutine state_init(this, nnode, nzone, stiffness, strength, hourglass)
    type(state_t), intent(out) :: this !< intent(out) frees and resets everything
    integer, intent(in) :: nnode, nzone
    logical, intent(in) :: stiffness !< hourglass stiffness state needed
    logical, intent(in) :: strength !< some material has strength: deviatoric state needed
    logical, intent(in), optional :: hourglass !< hourglass control on: its work is booked
    allocate(this%node_position(3, nnode), this%node_velocity(3, nnode), this%node_mass(nnode))
    allocate(this%node_force(3, nnode), this%node_position_old(3, nnode))
    allocate(this%node_velocity_old(3, nnode), this%node_velocity_half(3, nnode))
    allocate(this%zone_mass(nzone), this%zone_volume(nzone), this%zone_density(nzone))
    allocate(this%zone_energy(nzone), this%zone_energy_old(nzone), this%zone_pressure(nzone))
    allocate(this%zone_viscosity(nzone), this%zone_sound_speed(nzone), this%zone_length(nzone))
    allocate(this%zone_divergence(nzone), this%zone_bmatrix(3, 8, nzone))
    allocate(this%corner_force(3, 8, nzone))
    allocate(this%zone_gradient(3, nzone))
    this%zone_gradient = 0.0_rk
    if (stiffness) then
      allocate(this%zone_hourglass(3, 4, nzone), this%zone_hourglass_new(3, 4, nzone))
      this%zone_hourglass = 0.0_rk
      this%zone_hourglass_new = 0.0_rk
    end if
    if (strength) then
      allocate(this%zone_stress(6, nzone), this%zone_stress_half(6, nzone))
      allocate(this%zone_plastic_strain(nzone))
      this%zone_stress = 0.0_rk
      this%zone_stress_half = 0.0_rk
      this%zone_plastic_strain = 0.0_rk
      allocate(this%zone_plastic_work(nzone))
      this%zone_plastic_work = 0.0_rk
    end if
    if (present(hourglass)) then
      if (hourglass) then
        allocate(this%zone_hourglass_work(nzone))
        this%zone_hourglass_work = 0.0_rk
      end if
    end if
    this%node_position = 0.0_rk
    this%node_velocity = 0.0_rk
    this%node_mass = 0.0_rk
    this%node_force = 0.0_rk
    this%node_position_old = 0.0_rk
    this%node_velocity_old = 0.0_rk
    this%node_velocity_half = 0.0_rk
    this%zone_mass = 0.0_rk
    this%zone_volume = 0.0_rk
    this%zone_density = 0.0_rk
    this%zone_energy = 0.0_rk
    this%zone_energy_old = 0.0_rk
    this%zone_pressure = 0.0_rk
    this%zone_viscosity = 0.0_rk
    this%zone_sound_speed = 0.0_rk
    this%zone_length = 0.0_rk
    this%zone_divergence = 0.0_rk
    this%zone_bmatrix = 0.0_rk
    this%corner_force = 0.0_rk
  end subroutine state_init

end module hydro_state
