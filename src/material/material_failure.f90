!> Material failure: the failure models (an abstract type with one deferred
!> procedure, the failure strain, and one factory, failure_model_new: the only
!> place that turns the deck's `failure` into a type), a material's failure
!> data (model, spall strength, erosion) and the distortion erosion of the
!> &erosion group. The damage D = sum(deps_p / eps_f) is a zone field of the
!> hydro state, advanced next to the plastic strain (hydro_strength_update);
!> a zone fails when D reaches 1 (docs/theory.md, "Failure and erosion").
module material_failure
  use core_kinds, only: rk
  use material_table, only: material_t, STRENGTH_JOHNSON_COOK
  use material_flow_stress, only: temperature_from_energy
  implicit none
  private
  public :: failure_model_new, failure_damage_rate, failure_homologous

  !> Deck names of the failure models (&material failure), for messages.
  character(len=*), parameter, public :: FAILURE_NAMES = 'johnson_cook, plastic_strain'
  !> Smallest failure strain used: where Johnson-Cook's formula gives less
  !> (a negative D1 at high triaxiality), the zone fails at its next plastic
  !> increment of 1e-6 (no division by a vanishing strain).
  real(rk), parameter, public :: FAILURE_STRAIN_FLOOR = 1.0e-6_rk

  !> A failure model: the equivalent plastic strain at failure of a zone in a
  !> given state.
  type, abstract, public :: failure_model_t
  contains
    procedure(strain_interface), deferred :: failure_strain
  end type failure_model_t

  abstract interface
    !> Failure strain at stress triaxiality sigma* = -p / sigma_vm, plastic
    !> strain rate over the reference rate, homologous temperature T*.
    pure function strain_interface(this, triaxiality, rate_ratio, homologous) result(eps_f)
      import :: failure_model_t, rk
      class(failure_model_t), intent(in) :: this
      real(rk), intent(in) :: triaxiality, rate_ratio, homologous
      real(rk) :: eps_f
    end function strain_interface
  end interface

  !> Johnson & Cook (Eng. Fract. Mech. 21 (1985) 31-48):
  !> eps_f = [D1 + D2 exp(D3 sigma*)] [1 + D4 ln(max(epsdot*, 1))] [1 + D5 T*].
  type, extends(failure_model_t), public :: jc_failure_t
    real(rk) :: d(5) = 0.0_rk !< D1 .. D5
  contains
    procedure :: failure_strain => jc_failure_strain
  end type jc_failure_t

  !> Maximum equivalent plastic strain: eps_f constant.
  type, extends(failure_model_t), public :: plastic_strain_failure_t
    real(rk) :: eps_f = 0.0_rk
  contains
    procedure :: failure_strain => plastic_failure_strain
  end type plastic_strain_failure_t

  !> A material's failure data (&material failure, jc_damage, failure_strain,
  !> spall_strength, erode). No model and no spall strength: the material
  !> never fails.
  type, public :: failure_t
    class(failure_model_t), allocatable :: model !< unallocated: no damage model
    real(rk) :: spall_strength = -1.0_rk !< > 0: p < -spall_strength fails the zone; < 0: none
    logical :: erode = .false. !< a failed zone is eroded (else it keeps no shear, no tension)
    real(rk) :: rate_reference = 1.0_rk !< reference strain rate of epsdot* (deck units)
  contains
    procedure :: fails => failure_fails
  end type failure_t

  !> Distortion erosion (&erosion): a zone of the given blocks is eroded when
  !> its relative volume V/V0 falls below volume_ratio, or its own time-step
  !> limit below dt_fraction of the run's first stable step.
  type, public :: erosion_spec_t
    logical :: given = .false. !< the deck has an &erosion group
    real(rk) :: volume_ratio = 0.0_rk !< 0: off
    real(rk) :: dt_fraction = 0.0_rk !< 0: off
    logical, allocatable :: block(:) !< (nblock) the blocks it applies to
  end type erosion_spec_t

contains

  !> The one place that turns a deck's failure model name into a type. params:
  !> jc_damage (5 values) for 'johnson_cook', failure_strain (1) for
  !> 'plastic_strain'. ok false for an unknown name (model unallocated).
  subroutine failure_model_new(name, params, model, ok)
    character(len=*), intent(in) :: name
    real(rk), intent(in) :: params(:)
    class(failure_model_t), allocatable, intent(out) :: model
    logical, intent(out) :: ok
    ok = .true.
    select case (name)
    case ('johnson_cook')
      allocate(model, source=jc_failure_t(d=params(1:5)))
    case ('plastic_strain')
      allocate(model, source=plastic_strain_failure_t(eps_f=params(1)))
    case default
      ok = .false.
    end select
  end subroutine failure_model_new

  pure function jc_failure_strain(this, triaxiality, rate_ratio, homologous) result(eps_f)
    class(jc_failure_t), intent(in) :: this
    real(rk), intent(in) :: triaxiality, rate_ratio, homologous
    real(rk) :: eps_f
    eps_f = (this%d(1) + this%d(2) * exp(this%d(3) * triaxiality)) &
        * (1.0_rk + this%d(4) * log(max(rate_ratio, 1.0_rk))) &
        * (1.0_rk + this%d(5) * homologous)
  end function jc_failure_strain

  pure function plastic_failure_strain(this, triaxiality, rate_ratio, homologous) result(eps_f)
    class(plastic_strain_failure_t), intent(in) :: this
    real(rk), intent(in) :: triaxiality, rate_ratio, homologous
    real(rk) :: eps_f
    eps_f = this%eps_f
    if (.false.) eps_f = triaxiality + rate_ratio + homologous ! interface arguments unused
  end function plastic_failure_strain

  !> The material can fail (a damage model or a spall strength).
  elemental logical function failure_fails(this)
    class(failure_t), intent(in) :: this
    failure_fails = allocated(this%model) .or. this%spall_strength > 0.0_rk
  end function failure_fails

  !> dD/d(eps_p) = 1 / eps_f of a zone at pressure p with von Mises stress
  !> sbar (> 0), plastic strain rate rate and homologous temperature T*; eps_f
  !> at least FAILURE_STRAIN_FLOOR.
  pure real(rk) function failure_damage_rate(fail, p, sbar, rate, homologous) result(per_strain)
    type(failure_t), intent(in) :: fail
    real(rk), intent(in) :: p, sbar, rate, homologous
    real(rk) :: eps_f
    eps_f = fail%model%failure_strain(-p / sbar, rate / fail%rate_reference, homologous)
    per_strain = 1.0_rk / max(eps_f, FAILURE_STRAIN_FLOOR)
  end function failure_damage_rate

  !> Homologous temperature T* of a zone of material mat with specific internal
  !> energy e: Johnson-Cook's (T - Tr)/(Tm - Tr) in [0, 1], T from the
  !> constant specific heat as the flow stress takes it; 0 for the other
  !> strength models (no temperature in the failure strain).
  elemental real(rk) function failure_homologous(mat, e) result(homologous)
    type(material_t), intent(in) :: mat
    real(rk), intent(in) :: e
    real(rk) :: temperature
    homologous = 0.0_rk
    if (mat%strength /= STRENGTH_JOHNSON_COOK) return
    temperature = temperature_from_energy(max(e, 0.0_rk), mat%jc%cv, mat%jc%tr)
    homologous = min(max((temperature - mat%jc%tr) / (mat%jc%tm - mat%jc%tr), 0.0_rk), 1.0_rk)
  end function failure_homologous

end module material_failure
